//! Serde types of the intermediate form written by `derive/rocking_derive`
//! (one JSON file per kernel variant, `generated/ir/<variant>.json`).

use std::fmt;
use std::path::Path;

use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, Serialize, Serializer};

use crate::{Error, Result};

/// The only schema version this renderer understands.
pub const SCHEMA_VERSION: u32 = 1;

/// One kernel variant: a set of functions sharing one parameter vector.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Ir {
    /// Schema version, must be [`SCHEMA_VERSION`].
    pub schema: u32,
    /// Name and version of the Python generator.
    pub generator: String,
    /// CasADi version used for the derivation.
    pub casadi: String,
    /// Python source file of the model.
    pub source: String,
    /// Model family.
    pub model: String,
    /// Variant (= Rust module) name, snake_case and unique.
    pub variant: String,
    /// One-line title.
    pub title: String,
    /// One-line description of the model family.
    #[serde(default)]
    pub model_description: String,
    /// The model's shape function, in words.
    #[serde(default)]
    pub shape: String,
    /// The number n of deformation coordinates u_1..u_n (shape functions); 1 when absent.
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub coordinates: usize,
    /// Mass (and inertia) parameters this variant removes (fixed to zero before the derivation).
    #[serde(default)]
    pub removed: Vec<String>,
    /// Rigid column (u = 0): one degree of freedom.
    #[serde(default)]
    pub rigid: bool,
    /// Linearised in θ.
    #[serde(default)]
    pub small_angle: bool,
    /// Markdown description.
    #[serde(default)]
    pub doc: String,
    /// Parameter vector, in order.
    pub params: Vec<Param>,
    /// Generated functions, in order.
    pub functions: Vec<Function>,
    /// Where this IR was read from (for error messages); not part of the JSON.
    #[serde(skip)]
    pub origin: String,
}

fn one() -> usize {
    1
}

fn is_one(n: &usize) -> bool {
    *n == 1
}

/// One entry of the parameter vector.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Param {
    /// Parameter name (also the name of its index constant).
    pub name: String,
    /// Description.
    #[serde(default)]
    pub doc: String,
    /// Field of `crate::Physical` that supplies the value.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub physical: Option<String>,
    /// Fixed value used when there is no `physical` field.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub default: Option<Float>,
    /// Computed by the solver from the other parameters (`"modal_damping"`: an entry of the modal
    /// damping matrix of a model with several deformation coordinates), instead of either.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub derived: Option<String>,
    /// The kind of mass this parameter is (`column`, `lumped`, `base`), if it is one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<String>,
    /// A mass a scene may switch off.
    #[serde(default)]
    pub removable: bool,
    /// This is the inertia of the base mass named here.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia_of: Option<String>,
    /// This is the height (fraction of H) of the lumped mass named here.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height_of: Option<String>,
}

/// One generated function.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Function {
    /// Function name.
    pub name: String,
    /// Markdown description.
    #[serde(default)]
    pub doc: String,
    /// Inputs, in argument order.
    pub inputs: Vec<Input>,
    /// The single output.
    pub output: Output,
    /// The instruction tape.
    pub instructions: Vec<Instruction>,
    /// CasADi's own evaluation at a few points.
    #[serde(default)]
    pub golden: Vec<Golden>,
    /// Right-hand sides only: the order of `taylor_golden`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub taylor_order: Option<usize>,
    /// Right-hand sides only: Taylor coefficients 1..=`taylor_order` of the ODE's solution at a
    /// few points (the ground acceleration's input holds its coefficients), from CasADi's symbolic
    /// Lie derivatives; `output[(n - 1) * dim + i]` is coefficient n of component i. Read by the
    /// tests of the Taylor-mode kernels.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub taylor_golden: Vec<Golden>,
}

/// One function argument.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Input {
    /// Argument name.
    pub name: String,
    /// Description.
    #[serde(default)]
    pub doc: String,
    /// Names of the elements, in order.
    pub elements: Vec<String>,
    /// Passed as `f64` instead of `&[f64; n]` (needs exactly one element).
    #[serde(default)]
    pub scalar: bool,
    /// This is the parameter vector (passed as `&Params`).
    #[serde(default)]
    pub params: bool,
}

/// The function result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Output {
    /// Result name.
    pub name: String,
    /// Description.
    #[serde(default)]
    pub doc: String,
    /// Names of the elements, in order.
    pub elements: Vec<String>,
    /// Returned as `f64` instead of `[f64; n]` (needs exactly one element).
    #[serde(default)]
    pub scalar: bool,
}

/// A reference evaluation: inputs in input order (scalars as 1-element lists).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Golden {
    /// Input values.
    pub inputs: Vec<Vec<Float>>,
    /// Expected output.
    pub output: Vec<Float>,
}

/// An `f64` that (de)serialises as a JSON number or one of the strings
/// `"inf"`, `"-inf"`, `"nan"` (also accepts `"Infinity"`, `"-Infinity"`, `"NaN"`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Float(pub f64);

impl Serialize for Float {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let v = self.0;
        if v.is_nan() {
            s.serialize_str("nan")
        } else if v.is_infinite() {
            s.serialize_str(if v > 0.0 { "inf" } else { "-inf" })
        } else {
            s.serialize_f64(v)
        }
    }
}

impl<'de> Deserialize<'de> for Float {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let v = serde_json::Value::deserialize(d)?;
        float_from_value(&v).map(Float).map_err(de::Error::custom)
    }
}

fn float_from_value(v: &serde_json::Value) -> std::result::Result<f64, String> {
    match v {
        serde_json::Value::Number(n) => n
            .as_f64()
            .ok_or_else(|| format!("number {n} is not representable as f64")),
        serde_json::Value::String(s) => match s.as_str() {
            "inf" | "+inf" | "Infinity" | "+Infinity" => Ok(f64::INFINITY),
            "-inf" | "-Infinity" => Ok(f64::NEG_INFINITY),
            "nan" | "NaN" => Ok(f64::NAN),
            other => Err(format!(
                "expected a number or \"inf\", \"-inf\", \"nan\", found string {other:?}"
            )),
        },
        other => Err(format!("expected a number, found {other}")),
    }
}

/// One tape instruction. Work variables may be re-assigned.
#[derive(Debug, Clone, PartialEq)]
pub enum Instruction {
    /// `["input", dest, input, element]`: `w[dest] = inputs[input][element]`.
    Input {
        /// Work variable written.
        dest: usize,
        /// Index of the function input.
        input: usize,
        /// Element of that input.
        element: usize,
    },
    /// `["const", dest, value]`.
    Const {
        /// Work variable written.
        dest: usize,
        /// The constant.
        value: f64,
    },
    /// `["output", element, src]`: output element `element` = `w[src]`.
    Output {
        /// Output element written.
        element: usize,
        /// Work variable read.
        src: usize,
    },
    /// `[op, dest, args...]` for every other operation (validated when rendering).
    Op {
        /// CasADi operation name (`OP_*` lowercased without the prefix).
        op: String,
        /// Work variable written.
        dest: usize,
        /// Work variables read.
        args: Vec<usize>,
    },
}

impl Serialize for Instruction {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeSeq;
        let mut seq = s.serialize_seq(None)?;
        match self {
            Instruction::Input {
                dest,
                input,
                element,
            } => {
                seq.serialize_element("input")?;
                seq.serialize_element(dest)?;
                seq.serialize_element(input)?;
                seq.serialize_element(element)?;
            }
            Instruction::Const { dest, value } => {
                seq.serialize_element("const")?;
                seq.serialize_element(dest)?;
                seq.serialize_element(&Float(*value))?;
            }
            Instruction::Output { element, src } => {
                seq.serialize_element("output")?;
                seq.serialize_element(element)?;
                seq.serialize_element(src)?;
            }
            Instruction::Op { op, dest, args } => {
                seq.serialize_element(op)?;
                seq.serialize_element(dest)?;
                for a in args {
                    seq.serialize_element(a)?;
                }
            }
        }
        seq.end()
    }
}

impl<'de> Deserialize<'de> for Instruction {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Instruction;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("an instruction array [op, dest, args...]")
            }
            fn visit_seq<A: SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> std::result::Result<Instruction, A::Error> {
                let op: String = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::custom("empty instruction"))?;
                let mut rest: Vec<serde_json::Value> = Vec::new();
                while let Some(v) = seq.next_element()? {
                    rest.push(v);
                }
                let index = |i: usize| -> std::result::Result<usize, A::Error> {
                    let v = rest.get(i).ok_or_else(|| {
                        de::Error::custom(format!("instruction {op:?}: missing operand {i}"))
                    })?;
                    v.as_u64()
                        .and_then(|n| usize::try_from(n).ok())
                        .ok_or_else(|| {
                            de::Error::custom(format!(
                                "instruction {op:?}: operand {i} must be a non-negative integer, found {v}"
                            ))
                        })
                };
                let arity = |n: usize| -> std::result::Result<(), A::Error> {
                    if rest.len() == n {
                        Ok(())
                    } else {
                        Err(de::Error::custom(format!(
                            "instruction {op:?}: expected {n} operands, found {}",
                            rest.len()
                        )))
                    }
                };
                Ok(match op.as_str() {
                    "input" => {
                        arity(3)?;
                        Instruction::Input {
                            dest: index(0)?,
                            input: index(1)?,
                            element: index(2)?,
                        }
                    }
                    "const" => {
                        arity(2)?;
                        let value = float_from_value(&rest[1]).map_err(|e| {
                            de::Error::custom(format!("instruction \"const\": {e}"))
                        })?;
                        Instruction::Const {
                            dest: index(0)?,
                            value,
                        }
                    }
                    "output" => {
                        arity(2)?;
                        Instruction::Output {
                            element: index(0)?,
                            src: index(1)?,
                        }
                    }
                    _ => {
                        if rest.is_empty() {
                            return Err(de::Error::custom(format!(
                                "instruction {op:?}: missing destination"
                            )));
                        }
                        let dest = index(0)?;
                        let args = (1..rest.len()).map(index).collect::<Result<_, _>>()?;
                        Instruction::Op {
                            op: op.clone(),
                            dest,
                            args,
                        }
                    }
                })
            }
        }
        d.deserialize_seq(V)
    }
}

impl Ir {
    /// Parses an IR document; `origin` names it in error messages.
    pub fn from_json(text: &str, origin: &str) -> Result<Ir> {
        let mut ir: Ir = serde_json::from_str(text).map_err(|source| Error::Json {
            file: origin.to_string(),
            source,
        })?;
        ir.origin = origin.to_string();
        if ir.schema != SCHEMA_VERSION {
            return Err(Error::invalid(
                origin,
                format!(
                    "unsupported IR schema {} (this renderer understands {SCHEMA_VERSION})",
                    ir.schema
                ),
            ));
        }
        Ok(ir)
    }

    /// Reads and parses an IR file.
    pub fn load(path: &Path) -> Result<Ir> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Ir::from_json(&text, &path.display().to_string())
    }

    /// The name used for this IR in error messages.
    pub fn origin(&self) -> String {
        if self.origin.is_empty() {
            format!("{}.json", self.variant)
        } else {
            self.origin.clone()
        }
    }
}

/// Reads every `*.json` file of `dir` (sorted by file name).
pub fn load_dir(dir: &Path) -> Result<Vec<Ir>> {
    let entries = std::fs::read_dir(dir).map_err(|source| Error::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut paths = Vec::new();
    for entry in entries {
        let entry = entry.map_err(|source| Error::Io {
            path: dir.to_path_buf(),
            source,
        })?;
        let path = entry.path();
        if path.extension().is_some_and(|e| e == "json") && path.is_file() {
            paths.push(path);
        }
    }
    paths.sort();
    paths.iter().map(|p| Ir::load(p)).collect()
}
