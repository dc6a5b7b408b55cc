//! Snapshot tests of the rendered output for the hand-written fixture IRs.

use std::path::{Path, PathBuf};

use rocking_codegen::{render_all, render_mod, render_taylor, render_variant, Ir};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures")
}

fn fixture(name: &str) -> Ir {
    Ir::load(&fixtures().join(format!("{name}.json"))).unwrap()
}

#[test]
fn variant_ops() {
    insta::assert_snapshot!(render_variant(&fixture("ops")).unwrap());
}

#[test]
fn variant_rigid_block() {
    insta::assert_snapshot!(render_variant(&fixture("rigid_block")).unwrap());
}

/// The Taylor-mode twin of a rocking right-hand side (sin/cos pair, constants hoisted).
#[test]
fn taylor_rigid_block() {
    insta::assert_snapshot!(render_taylor(&fixture("rigid_block")).unwrap());
}

/// An operation without a Taylor recurrence in a Taylor-mode function is refused by name.
#[test]
fn taylor_refuses_an_operation_without_a_rule() {
    let mut ir = fixture("rigid_block");
    let f = &mut ir.functions[0];
    let op = f
        .instructions
        .iter_mut()
        .find_map(|ins| match ins {
            rocking_codegen::Instruction::Op { op, .. } if op == "sin" => Some(op),
            _ => None,
        })
        .expect("the fixture takes a sine");
    *op = "tan".to_string();
    let msg = render_taylor(&ir).unwrap_err().to_string();
    assert!(msg.contains("\"tan\" has no Taylor-mode rule"), "{msg}");
}

#[test]
fn mod_two_variants() {
    // Deliberately unsorted: mod.rs sorts by variant name.
    let irs = [fixture("rigid_block"), fixture("ops")];
    insta::assert_snapshot!(render_mod(&irs).unwrap());
}

#[test]
fn mod_one_variant() {
    insta::assert_snapshot!(render_mod(&[fixture("ops")]).unwrap());
}

#[test]
fn render_all_fixture_dir() {
    let files = render_all(&fixtures()).unwrap();
    let keys: Vec<&str> = files.keys().map(String::as_str).collect();
    assert_eq!(
        keys,
        [
            "generated/src/kernels/mod.rs",
            "generated/src/kernels/ops.rs",
            "generated/src/kernels/rigid_block.rs",
            "generated/src/taylor/mod.rs",
            "generated/src/taylor/ops.rs",
            "generated/src/taylor/rigid_block.rs",
        ]
    );
    assert_eq!(
        files["generated/src/kernels/ops.rs"],
        render_variant(&fixture("ops")).unwrap()
    );
}

#[test]
fn rendering_is_deterministic() {
    let a = render_all(&fixtures()).unwrap();
    let b = render_all(&fixtures()).unwrap();
    assert_eq!(a, b);
}

#[test]
fn unknown_op_is_an_error_naming_op_function_and_file() {
    let text = std::fs::read_to_string(fixtures().join("rigid_block.json"))
        .unwrap()
        .replace("\"sin\"", "\"erfinv\"");
    let ir = Ir::from_json(&text, "somewhere/rigid_block.json").unwrap();
    let err = render_variant(&ir).unwrap_err().to_string();
    assert!(err.contains("unknown op \"erfinv\""), "{err}");
    assert!(err.contains("\"rocking_rhs\""), "{err}");
    assert!(err.contains("somewhere/rigid_block.json"), "{err}");
}

#[test]
fn invalid_ir_errors_name_the_file() {
    // Compact JSON, so the replacements below have one spelling.
    let text = std::fs::read_to_string(fixtures().join("rigid_block.json")).unwrap();
    let base =
        serde_json::to_string(&serde_json::from_str::<serde_json::Value>(&text).unwrap()).unwrap();
    let edit = |from: &str, to: &str| {
        assert!(base.contains(from), "{from}");
        base.replace(from, to)
    };
    let cases = [
        // work variable read before written
        (edit("[\"sin\",1,1]", "[\"sin\",1,9]"), "w9 is read before"),
        // output element out of range
        (
            edit("[\"output\",1,1]", "[\"output\",7,1]"),
            "output element 7",
        ),
        // wrong arity
        (edit("[\"sin\",1,1]", "[\"sin\",1,1,1]"), "takes 1 argument"),
        // input element out of range
        (
            edit("[\"input\",0,0,1]", "[\"input\",0,0,5]"),
            "element 5 of input \"x\"",
        ),
        // a param with both sources
        (
            edit("\"physical\":\"b\"", "\"physical\":\"b\",\"default\":1.0"),
            "exactly one of",
        ),
        // schema
        (
            edit("\"schema\":1", "\"schema\":2"),
            "unsupported IR schema 2",
        ),
        // not JSON of the right shape
        (edit("\"params\":[", "\"params\":3,\"x\":["), "invalid IR"),
    ];
    for (text, want) in cases {
        let err = Ir::from_json(&text, "x/rigid_block.json")
            .and_then(|ir| render_variant(&ir))
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("x/rigid_block.json: "), "{err}");
        assert!(err.contains(want), "{err} (wanted {want:?})");
    }
}

#[test]
fn empty_mod_renders() {
    insta::assert_snapshot!(render_mod(&[]).unwrap());
}
