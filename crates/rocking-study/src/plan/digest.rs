//! Fingerprints: a record's contents and the running program, so that a journal is reused only
//! by the same build on the same bytes.

use std::path::Path;

use rocking_scene::SceneError;
use rocking_spectra::fnv1a;

/// A digest of a file's contents: results computed from a record are reused only while the
/// record's bytes are the same.
pub fn file_digest(path: &Path) -> Result<String, SceneError> {
    let bytes = std::fs::read(path)
        .map_err(|e| SceneError::input(format!("{}: cannot read: {e}", path.display())))?;
    Ok(format!("{:016x}", fnv1a(&bytes)))
}

/// A digest of the running program (its executable), so that a journal written by another build
/// is not reused; the package version when the executable cannot be read.
pub fn program_digest() -> &'static str {
    static DIGEST: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    DIGEST.get_or_init(
        || match std::env::current_exe().and_then(|exe| executable_hash(&exe)) {
            Ok(hash) => format!("{} {hash:016x}", env!("CARGO_PKG_VERSION")),
            Err(_) => env!("CARGO_PKG_VERSION").to_string(),
        },
    )
}

/// FxHash of a file's bytes, read through one reused 1 MiB buffer: reading the ~20 MB executable
/// whole into a fresh allocation cost a page fault per 4 KiB (about 2 % of a 100 × 100
/// spectrum's samples, `perf record`). Every chunk but the last is full, so the hash does not
/// depend on how the operating system splits the reads.
fn executable_hash(path: &Path) -> std::io::Result<u64> {
    use std::hash::Hasher as _;
    use std::io::Read as _;
    const CHUNK: usize = 1 << 20;
    let mut file = std::fs::File::open(path)?;
    let mut buf = Vec::with_capacity(CHUNK);
    let mut h = rustc_hash::FxHasher::default();
    loop {
        buf.clear();
        let n = (&mut file).take(CHUNK as u64).read_to_end(&mut buf)?;
        h.write(&buf);
        if n < CHUNK {
            return Ok(h.finish());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::executable_hash;

    /// The hash follows every byte of a file of several chunks, the last one partial, and
    /// nothing else: the same bytes in another file give the same hash.
    #[test]
    fn executable_hash_follows_the_bytes_across_chunks() {
        let dir = tempfile::tempdir().unwrap();
        let bytes: Vec<u8> = (0..(5 << 19) + 123)
            .map(|i: u32| (i * 7 % 251) as u8)
            .collect();
        let write = |name: &str, b: &[u8]| {
            let p = dir.path().join(name);
            std::fs::write(&p, b).unwrap();
            executable_hash(&p).unwrap()
        };
        let base = write("a", &bytes);
        assert_eq!(write("b", &bytes), base, "same bytes, another file");
        for at in [0, (1 << 20) - 1, 1 << 20, bytes.len() - 1] {
            let mut changed = bytes.clone();
            changed[at] ^= 1;
            assert_ne!(write("c", &changed), base, "byte {at} flipped");
        }
        assert_ne!(
            write("d", &bytes[..bytes.len() - 1]),
            base,
            "one byte shorter"
        );
        assert_ne!(
            write("e", &bytes[..1 << 20]),
            base,
            "cut at a chunk boundary"
        );
    }
}
