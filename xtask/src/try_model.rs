//! `cargo xtask try-model`: the model developer's path, end to end, in a temporary copy.
//!
//! A model developer edits `derive/rocking_derive/models.py`, runs `cargo xtask regen` and
//! expects everything downstream to keep working. This command does exactly that to a copy of
//! the workspace (the files git knows, committed or not): it appends a new model to `models.py`
//! ([`NEW_MODEL`]: another shape function and another added mass, with its own parameter),
//! regenerates, runs the tests of the generated crate, the codegen crate and the freshness check
//! there, and then runs a scene that names the new model and sets its parameter ([`scene_text`]) with
//! the `rocking` command built in the copy: no hand-written Rust is edited. Its derived quantities
//! must match the closed forms of that model ([`closed_forms`]). The same change adds a model of two
//! deformation coordinates (the same masses on the basis η², η³), whose fixed-base and uplifted
//! frequencies must match the roots of its 2 × 2 pencils written out by hand
//! ([`two_coordinate_frequencies`]) and whose run must balance its energy. The working tree is
//! never touched.
//!
//! The copy regenerates with `regen --only parabolic_tank,parabolic_tank2`: CI's own
//! `regen --check` steps derive every variant already, so here only the two new models are
//! derived (a fraction of the full derivation's time) and every file is rendered from their IR
//! and the checked-in IR of the others.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::venv;
use crate::Result;

/// The change a model developer makes: a model that is neither of the kept examples (shape
/// ψ = η², a lumped tank mass `m_t` at 3/4 H with its own parameter), the same masses on a basis
/// of two shape functions (η², η³: two deformation coordinates), and their kernel variants.
pub const NEW_MODEL: &str = r#"

# --- appended by `cargo xtask try-model` in a temporary copy: a model developer's change ---
TRY_MODEL = Model(
    name="parabolic_tank",
    description="Top mass, a tank m_t at 3/4 H and a base, on a column deflecting as psi = eta^2",
    shape=Polynomial("psi = eta^2", {2: Fraction(1)}),
    masses=(LumpedMass("m", removable=False), LumpedMass("m_t", Fraction(3, 4)), BaseMass("m_b", "i_bc")),
    extra_params=(Param("m_t", "mass of the tank at 3/4 H", default=0.0),),
)
TRY_MODEL2 = Model(
    name="parabolic_tank2",
    description="The masses of parabolic_tank on a column deflecting as u_1 eta^2 + u_2 eta^3",
    shape=(Polynomial("eta^2", {2: Fraction(1)}), Polynomial("eta^3", {3: Fraction(1)})),
    masses=TRY_MODEL.masses,
    extra_params=TRY_MODEL.extra_params,
)
VARIANTS = VARIANTS + (
    Variant("parabolic_tank", "Try-model: top mass and a tank on a parabolic column", "", TRY_MODEL),
    Variant("parabolic_tank2", "Try-model: the same on two deformation coordinates", "", TRY_MODEL2),
)
"#;

/// The file the change is appended to.
const MODELS_PY: &str = "derive/rocking_derive/models.py";

/// Runs the whole path; the copy stays in `target/try-model/workspace` for inspection.
pub fn run(root: &Path) -> Result<()> {
    let python = venv::ensure(root)?;
    let base = root.join("target").join("try-model");
    let copy = base.join("workspace");
    if copy.exists() {
        std::fs::remove_dir_all(&copy).map_err(|e| format!("{}: {e}", copy.display()))?;
    }
    let n = copy_workspace(root, &copy)?;
    println!("xtask: try-model: copied {n} files to {}", copy.display());
    // The copy derives with the pinned environment of the working tree.
    let venv_dir = python
        .parent()
        .and_then(Path::parent)
        .ok_or("the virtual environment has no root")?;
    std::os::unix::fs::symlink(venv_dir, copy.join(".venv"))?;
    // Scenes may name records in ../shared, as beside the working tree.
    let shared = root.join("..").join("shared");
    let link = base.join("shared");
    if shared.is_dir() && std::fs::symlink_metadata(&link).is_err() {
        std::os::unix::fs::symlink(shared.canonicalize()?, &link)?;
    }

    let models = copy.join(MODELS_PY);
    let mut text =
        std::fs::read_to_string(&models).map_err(|e| format!("{}: {e}", models.display()))?;
    text.push_str(NEW_MODEL);
    std::fs::write(&models, text)?;
    println!(
        "xtask: try-model: appended the models `parabolic_tank` and `parabolic_tank2` to {MODELS_PY}"
    );

    let target = base.join("target");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    let cargo_in_copy = |args: &[&str]| {
        let mut cmd = Command::new(&cargo);
        // Unoptimised, without debug info: these tests are about correctness, and the copy's
        // dev and test builds then share their dependencies (one compile of each crate).
        cmd.args(args)
            .current_dir(&copy)
            .env("CARGO_TARGET_DIR", &target)
            .env("CARGO_PROFILE_TEST_OPT_LEVEL", "0")
            .env("CARGO_PROFILE_TEST_DEBUG", "0")
            .env("CARGO_PROFILE_DEV_DEBUG", "0");
        cmd
    };
    // Only the two new models are derived (CI's `regen --check` steps derive every variant
    // already); every file is rendered from their IR and the checked-in IR of the others.
    venv::run(&mut cargo_in_copy(&[
        "xtask",
        "regen",
        "--only",
        "parabolic_tank,parabolic_tank2",
    ]))?;
    for generated in [
        "generated/ir/parabolic_tank.json",
        "generated/src/kernels/parabolic_tank.rs",
        "generated/ir/parabolic_tank2.json",
        "generated/src/kernels/parabolic_tank2.rs",
    ] {
        if !copy.join(generated).is_file() {
            return Err(format!("regen did not write {generated}").into());
        }
    }
    venv::run(&mut cargo_in_copy(&[
        "test",
        "-p",
        "rocking-kernels",
        "-p",
        "rocking-codegen",
        "-p",
        "xtask",
    ]))?;
    println!(
        "xtask: try-model: a new model regenerated and the generated crate's, the codegen \
         crate's and the freshness tests passed in the copy"
    );

    let scene = copy.join("scenes").join("try-model.toml");
    std::fs::write(&scene, scene_text("parabolic_tank"))?;
    let rocking = |args: &[&str]| -> Result<serde_json::Value> {
        let mut cmd = cargo_in_copy(&["run", "--quiet", "-p", "rocking-cli", "--"]);
        cmd.args(args);
        println!("xtask: running {cmd:?}");
        let out = cmd.output().map_err(|e| format!("cannot run cargo: {e}"))?;
        if !out.status.success() {
            return Err(format!(
                "rocking {} failed with {}:\n{}",
                args.join(" "),
                out.status,
                String::from_utf8_lossy(&out.stderr)
            )
            .into());
        }
        Ok(serde_json::from_slice(&out.stdout)?)
    };
    let scene_arg = scene.to_str().ok_or("non-UTF-8 path")?;
    let check = rocking(&["check", scene_arg, "--json"])?;
    let want = closed_forms(ALPHA, OMEGA_N, M_T, GAMMA_MB, GAMMA_IB);
    let got = |key: &str| -> Result<f64> {
        check["derived"][key]
            .as_f64()
            .ok_or_else(|| format!("rocking check --json has no number derived.{key}").into())
    };
    let ei = check["params"]["ei"]
        .as_f64()
        .ok_or("rocking check --json has no number params.ei")?;
    let model = check["model"].as_str().unwrap_or_default();
    let variant = check["kernel_variant"].as_str().unwrap_or_default();
    println!("xtask: try-model: `rocking check` runs model {model}, kernel variant {variant}");
    if model != "parabolic_tank" || variant != "parabolic_tank" {
        return Err(format!("the scene ran model {model:?} / variant {variant:?}").into());
    }
    let rows = [
        (
            "omega_up / omega_n",
            got("omega_up")? / got("omega_n")?,
            want.modal_s,
        ),
        ("E_ref", got("e_ref")?, want.e_ref),
        ("EI", ei, want.ei),
    ];
    let mut worst: f64 = 0.0;
    for (name, have, closed) in rows {
        let rel = (have - closed).abs() / closed.abs();
        worst = worst.max(rel);
        println!("xtask: try-model: {name} = {have:.15e}, closed form {closed:.15e}, relative difference {rel:.1e}");
    }
    if worst.is_nan() || worst > 1e-12 {
        return Err(format!("derived quantities differ from the closed forms by {worst:e}").into());
    }
    let run_dir = |name: &str| target.join(name).to_str().map(str::to_owned);
    let balanced = |run: &serde_json::Value, model: &str| -> Result<()> {
        let residual = run["energy_balance_residual"]
            .as_f64()
            .ok_or("the run has no energy balance residual")?;
        let max_theta = run["max_theta_over_alpha"]
            .as_f64()
            .ok_or("the run has no max_theta_over_alpha")?;
        println!("xtask: try-model: `rocking run` of {model}: max θ/α = {max_theta:.4}, energy balance residual {residual:.1e} E_ref");
        if residual.is_nan() || residual.abs() > 1e-6 || !max_theta.is_finite() {
            return Err(format!("the run of {model} does not balance its energy").into());
        }
        Ok(())
    };
    let out = run_dir("try-model-run").ok_or("non-UTF-8 path")?;
    balanced(
        &rocking(&["run", scene_arg, "--json", "--out", &out])?,
        "parabolic_tank",
    )?;

    // The same masses on two deformation coordinates.
    let scene2 = copy.join("scenes").join("try-model2.toml");
    std::fs::write(&scene2, scene_text("parabolic_tank2"))?;
    let scene2_arg = scene2.to_str().ok_or("non-UTF-8 path")?;
    let check = rocking(&["check", scene2_arg, "--json"])?;
    let list = |key: &str| -> Result<Vec<f64>> {
        let values = check["derived"][key].as_array().ok_or_else(|| {
            format!("rocking check --json of parabolic_tank2 has no list derived.{key}")
        })?;
        Ok(values
            .iter()
            .filter_map(serde_json::Value::as_f64)
            .collect())
    };
    let want = two_coordinate_frequencies(ALPHA, OMEGA_N, M_T, GAMMA_MB, GAMMA_IB);
    let mut worst: f64 = 0.0;
    for (key, closed) in [
        ("fixed_base_frequencies", want.fixed_base),
        ("uplifted_frequencies", want.uplifted),
    ] {
        let have = list(key)?;
        if have.len() != 2 {
            return Err(format!("parabolic_tank2: derived.{key} = {have:?}, not two").into());
        }
        for (k, (have, closed)) in have.iter().zip(closed).enumerate() {
            let rel = (have - closed).abs() / closed;
            worst = worst.max(rel);
            println!("xtask: try-model: parabolic_tank2 {key}[{k}] = {have:.15e}, by hand {closed:.15e}, relative difference {rel:.1e}");
        }
    }
    let ei = check["params"]["ei"]
        .as_f64()
        .ok_or("rocking check --json of parabolic_tank2 has no number params.ei")?;
    let rel = (ei - want.ei).abs() / want.ei;
    println!("xtask: try-model: parabolic_tank2 EI = {ei:.15e}, by hand {:.15e}, relative difference {rel:.1e}", want.ei);
    worst = worst.max(rel);
    if worst.is_nan() || worst > 1e-12 {
        return Err(format!(
            "parabolic_tank2's frequencies differ from the pencils' roots by {worst:e}"
        )
        .into());
    }
    let out = run_dir("try-model-run2").ok_or("non-UTF-8 path")?;
    balanced(
        &rocking(&["run", scene2_arg, "--json", "--out", &out])?,
        "parabolic_tank2",
    )?;
    println!("xtask: try-model: passed");
    Ok(())
}

/// The new models' scene (dimensionless, R = g = m = 1): their own parameter `m_t` is set.
const ALPHA: f64 = 0.15;
const OMEGA_N: f64 = 6.0;
const M_T: f64 = 0.7;
const GAMMA_MB: f64 = 1.5;
const GAMMA_IB: f64 = 1.1;
fn scene_text(model: &str) -> String {
    format!(
        r#"title = "cargo xtask try-model: the model {model}, added in a temporary copy"

[structure]
model = "{model}"
m_t = {M_T}
omega_n_over_p = {OMEGA_N}
alpha = {ALPHA}
gamma_mc = 0.0
gamma_mb = {GAMMA_MB}
gamma_ib = {GAMMA_IB}
zeta = 0.0
damping = "fixed-base"

[excitation]
kind = "sine-pulse"
omega_p_over_p = 3.0
amplitude = 2.5

[effects]
impact = "vvel"
energy = true

[solver]
accuracy = "reference"
after_excitation = 5.0
"#
    )
}

/// Closed forms of the new model (ψ = η², masses m = 1 at H, m_t at 3/4 H with ψ(3/4) = 9/16,
/// a base m_b with inertia I_bc about a corner), dimensionless: B = sin α, H = cos α.
pub struct ClosedForms {
    /// ω_up/ω_n = sqrt(J0 / (J0 − M_ut²/M_uu)) (equations.md 1.6).
    pub modal_s: f64,
    /// g (sqrt((M B)² + (S1 H)²) − S1 H) of the rigid column with all masses.
    pub e_ref: f64,
    /// EI = ω_n² M_uu H³ / ∫ψ''², with ∫(ψ'')² = 4.
    pub ei: f64,
}

/// The closed forms for slenderness `alpha`, `omega_n` = ω_n/p, tank mass `m_t`, base ratios.
pub fn closed_forms(
    alpha: f64,
    omega_n: f64,
    m_t: f64,
    gamma_mb: f64,
    gamma_ib: f64,
) -> ClosedForms {
    let (b, h) = alpha.sin_cos();
    let m_b = gamma_mb;
    let i_bc = gamma_ib * 4.0 / 3.0 * m_b * b * b;
    let j0 = i_bc + (b * b + h * h) + m_t * (b * b + 9.0 / 16.0 * h * h);
    let m_ut = h * (1.0 + 27.0 / 64.0 * m_t);
    let m_uu = 1.0 + 81.0 / 256.0 * m_t;
    let m_tot = 1.0 + m_t + m_b;
    let s1h = h * (1.0 + 0.75 * m_t);
    ClosedForms {
        modal_s: (j0 / (j0 - m_ut * m_ut / m_uu)).sqrt(),
        e_ref: (m_tot * b).hypot(s1h) - s1h,
        ei: omega_n * omega_n * m_uu * h.powi(3) / 4.0,
    }
}

/// Copies every file git knows (tracked, or untracked and not ignored) from `root` to `dest`.
fn copy_workspace(root: &Path, dest: &Path) -> Result<usize> {
    let out = Command::new("git")
        .args([
            "ls-files",
            "-z",
            "--cached",
            "--others",
            "--exclude-standard",
        ])
        .current_dir(root)
        .output()
        .map_err(|e| format!("cannot run git ls-files: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "git ls-files failed: {}",
            String::from_utf8_lossy(&out.stderr)
        )
        .into());
    }
    let mut n = 0;
    for name in out.stdout.split(|b| *b == 0).filter(|s| !s.is_empty()) {
        let rel = PathBuf::from(String::from_utf8_lossy(name).into_owned());
        let from = root.join(&rel);
        if !from.is_file() {
            continue; // deleted in the working tree
        }
        let to = dest.join(&rel);
        if let Some(dir) = to.parent() {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        std::fs::copy(&from, &to).map_err(|e| format!("{}: {e}", from.display()))?;
        n += 1;
    }
    Ok(n)
}

/// The natural frequencies of `parabolic_tank2`, written out by hand: masses 1 at H and `m_t` at
/// 3/4 H, no column mass (the scene's γ_mc = 0), ψ_1 = η², ψ_2 = η³.
pub struct TwoCoordinates {
    /// The roots ω of det(K − ω² M) = 0, ascending; EI is set so that the first is ω_n.
    pub fixed_base: [f64; 2],
    /// The roots ω of det(K − ω² (M − c cᵀ / J0)) = 0, ascending.
    pub uplifted: [f64; 2],
    /// EI = ω_n² / λ_1, λ_1 the first root at EI = 1.
    pub ei: f64,
}

/// [`TwoCoordinates`] for the scene's parameters. M_ij = ψ_i(1) ψ_j(1) + m_t ψ_i(¾) ψ_j(¾);
/// K_ij = EI/H³ ∫ψ_i''ψ_j'' dη = EI/H³ [[4, 6], [6, 12]]; c_i = ∂²T/∂θ'∂u_i' = H (ψ_i(1) + ¾ m_t
/// ψ_i(¾)) (the horizontal velocity of each mass is its height times θ' plus its deflection rate,
/// at θ = u = 0); J0 as in [`closed_forms`].
pub fn two_coordinate_frequencies(
    alpha: f64,
    omega_n: f64,
    m_t: f64,
    gamma_mb: f64,
    gamma_ib: f64,
) -> TwoCoordinates {
    let (b, h) = alpha.sin_cos();
    let i_bc = gamma_ib * 4.0 / 3.0 * gamma_mb * b * b;
    let j0 = i_bc + (b * b + h * h) + m_t * (b * b + 9.0 / 16.0 * h * h);
    let psi = |eta: f64| [eta * eta, eta * eta * eta];
    let (top, tank) = (psi(1.0), psi(0.75));
    let mass = |i: usize, j: usize| top[i] * top[j] + m_t * tank[i] * tank[j];
    let c = |i: usize| h * (top[i] + 0.75 * m_t * tank[i]);
    // K at EI = 1; the roots of det(K − λ M) = 0 for a symmetric 2 × 2 pencil, ascending.
    let k = [[4.0, 6.0], [6.0, 12.0]].map(|row| row.map(|v| v / h.powi(3)));
    let roots = |m: [[f64; 2]; 2]| {
        let a = m[0][0] * m[1][1] - m[0][1] * m[0][1];
        let b = -(k[0][0] * m[1][1] + k[1][1] * m[0][0] - 2.0 * k[0][1] * m[0][1]);
        let c = k[0][0] * k[1][1] - k[0][1] * k[0][1];
        let d = (b * b - 4.0 * a * c).sqrt();
        // The smaller root by the product of the roots, free of cancellation.
        let large = (-b + d) / (2.0 * a);
        [c / (a * large), large]
    };
    let fixed = roots([[mass(0, 0), mass(0, 1)], [mass(0, 1), mass(1, 1)]]);
    let up = |i: usize, j: usize| mass(i, j) - c(i) * c(j) / j0;
    let uplifted = roots([[up(0, 0), up(0, 1)], [up(0, 1), up(1, 1)]]);
    // EI = ω_n² / λ_1 makes the first fixed-base frequency ω_n; every root scales with EI.
    let ei = omega_n * omega_n / fixed[0];
    TwoCoordinates {
        fixed_base: fixed.map(|l| (ei * l).sqrt()),
        uplifted: uplifted.map(|l| (ei * l).sqrt()),
        ei,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rayleigh–Ritz: the basis {η², η³} contains the one-coordinate model's η², so at the same EI
    /// its first fixed-base frequency is at most that model's (k̃ = 4 EI/H³, m̃ = M_uu of
    /// [`closed_forms`]), and uplifting (M − c cᵀ/J0 < M) raises both frequencies.
    #[test]
    fn two_coordinate_frequencies_bound_the_one_coordinate_model() {
        let two = two_coordinate_frequencies(ALPHA, OMEGA_N, M_T, GAMMA_MB, GAMMA_IB);
        assert!((two.fixed_base[0] - OMEGA_N).abs() < 1e-12 * OMEGA_N);
        // The one-coordinate model at the two-coordinate scene's EI.
        let m_uu = 1.0 + 81.0 / 256.0 * M_T;
        let omega_one = (4.0 * two.ei / ALPHA.cos().powi(3) / m_uu).sqrt();
        assert!(two.fixed_base[0] < omega_one * (1.0 - 1e-6));
        // Equivalently: the one-coordinate model needs a larger EI for the same ω_n.
        let one = closed_forms(ALPHA, OMEGA_N, M_T, GAMMA_MB, GAMMA_IB);
        assert!(two.ei > one.ei * (1.0 + 1e-6));
        for k in 0..2 {
            assert!(two.uplifted[k] > two.fixed_base[k] * (1.0 + 1e-6));
        }
        assert!(two.fixed_base[1] > two.fixed_base[0]);
    }
}
