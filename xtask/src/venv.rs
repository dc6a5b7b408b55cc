//! The pinned Python environment of the derivation (`<repo>/.venv`).

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::Result;

/// Name of the stamp file kept inside the virtual environment.
const STAMP: &str = ".rocking-requirements.stamp";

/// FNV-1a, 64 bit (the `fnv` crate's): a stable hash of the pinned requirements (not for security).
pub(crate) fn fnv1a64(bytes: &[u8]) -> u64 {
    use std::hash::Hasher as _;
    let mut h = fnv::FnvHasher::default();
    h.write(bytes);
    h.finish()
}

fn venv_python(venv: &Path) -> PathBuf {
    if cfg!(windows) {
        venv.join("Scripts").join("python.exe")
    } else {
        venv.join("bin").join("python")
    }
}

/// Runs a command, echoing it; a non-zero exit is an error.
pub(crate) fn run(cmd: &mut Command) -> Result<()> {
    println!("xtask: running {cmd:?}");
    let status = cmd
        .status()
        .map_err(|e| format!("cannot run {:?}: {e}", cmd.get_program()))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("{cmd:?} failed with {status}").into())
    }
}

/// Makes sure `<root>/.venv` exists with the pins of `derive/requirements.txt`
/// installed, and returns its Python interpreter.
///
/// The virtual environment is created with `$PYTHON` (default `python3`). The
/// requirements are (re-)installed only when the hash of `requirements.txt` differs
/// from the one recorded in the stamp file inside the environment.
pub fn ensure(root: &Path) -> Result<PathBuf> {
    let venv = root.join(".venv");
    let requirements = root.join("derive").join("requirements.txt");
    let pins =
        std::fs::read(&requirements).map_err(|e| format!("{}: {e}", requirements.display()))?;
    let python = venv_python(&venv);

    if !python.exists() {
        let base = std::env::var("PYTHON").unwrap_or_else(|_| "python3".to_string());
        println!(
            "xtask: creating the Python virtual environment {} with {base}",
            venv.display()
        );
        run(Command::new(&base).arg("-m").arg("venv").arg(&venv))?;
    }

    let stamp_path = venv.join(STAMP);
    let want = format!("fnv1a64 {:016x} derive/requirements.txt\n", fnv1a64(&pins));
    let have = std::fs::read_to_string(&stamp_path).unwrap_or_default();
    if have == want {
        println!(
            "xtask: {} is up to date with derive/requirements.txt",
            venv.display()
        );
    } else {
        println!("xtask: installing the pinned packages of derive/requirements.txt");
        run(Command::new(&python)
            .args(["-m", "pip", "install", "--disable-pip-version-check", "-r"])
            .arg(&requirements))?;
        std::fs::write(&stamp_path, want).map_err(|e| format!("{}: {e}", stamp_path.display()))?;
    }
    Ok(python)
}

#[cfg(test)]
mod tests {
    use super::fnv1a64;

    #[test]
    fn fnv_reference_values() {
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
    }
}
