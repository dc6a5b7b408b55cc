//! The generated kernels reproduce the golden samples stored in each
//! `generated/ir/*.json` to 1e-12 relative: the instruction tape replayed in f64 by the derivation
//! (elementary functions correctly rounded, so the samples are the same on every machine), itself
//! checked there against CasADi's own evaluation.

use std::path::Path;

use serde_json::Value;

fn number(v: &Value) -> f64 {
    match v {
        Value::Number(n) => n.as_f64().unwrap(),
        Value::String(s) if s == "inf" => f64::INFINITY,
        Value::String(s) if s == "-inf" => f64::NEG_INFINITY,
        Value::String(s) if s == "nan" => f64::NAN,
        other => panic!("not a number: {other}"),
    }
}

#[test]
fn kernels_reproduce_casadi_golden_samples() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("ir");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json")) // ground/: tests/ground.rs
        .collect();
    files.sort();
    assert!(
        files.len() >= 6,
        "expected the IR of every variant in {}",
        dir.display()
    );
    let (mut checked, mut worst) = (0usize, 0.0f64);
    for file in files {
        let ir: Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
        let variant = ir["variant"].as_str().unwrap();
        for function in ir["functions"].as_array().unwrap() {
            let name = function["name"].as_str().unwrap();
            for sample in function["golden"].as_array().unwrap() {
                let inputs: Vec<Vec<f64>> = sample["inputs"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|i| i.as_array().unwrap().iter().map(number).collect())
                    .collect();
                let refs: Vec<&[f64]> = inputs.iter().map(|v| v.as_slice()).collect();
                let got = rocking_kernels::kernels::call(variant, name, &refs)
                    .unwrap_or_else(|| panic!("{variant}::{name} cannot be called"));
                let want: Vec<f64> = sample["output"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(number)
                    .collect();
                assert_eq!(got.len(), want.len(), "{variant}::{name}: output length");
                for (k, (g, w)) in got.iter().zip(&want).enumerate() {
                    if w.is_infinite() || w.is_nan() {
                        assert!(
                            g == w || (g.is_nan() && w.is_nan()),
                            "{variant}::{name}[{k}]: {g} vs {w}"
                        );
                        continue;
                    }
                    let err = (g - w).abs() / w.abs().max(1e-300);
                    let err = if w.abs() < 1e-300 { (g - w).abs() } else { err };
                    worst = worst.max(err);
                    assert!(
                        err <= 1e-12,
                        "{variant}::{name}[{k}]: {g} vs golden {w} (rel {err:e})"
                    );
                }
                checked += 1;
            }
        }
    }
    eprintln!("golden: {checked} samples, worst relative error {worst:e}");
    assert!(checked > 100);
}
