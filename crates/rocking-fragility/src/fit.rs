//! Lognormal fragility curves P(collapse | IM = x) = Φ(ln(x/θ)/β) fitted by
//! maximum likelihood, from IDA capacities or from multiple-stripe counts.

use crate::{normal, ArgumentError, FragilityError, NoFit};

/// A lognormal fragility curve: median θ (in the IM's units) and dispersion β.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lognormal {
    /// Median θ: the IM with a 50 % probability of collapse.
    pub theta: f64,
    /// Logarithmic standard deviation β.
    pub beta: f64,
}

impl Lognormal {
    /// P(collapse | IM = `im`) = Φ(ln(im/θ)/β); 0 for im ≤ 0.
    pub fn probability(&self, im: f64) -> f64 {
        if im > 0.0 {
            normal::cdf((im / self.theta).ln() / self.beta)
        } else {
            0.0
        }
    }
}

/// One stripe of a multiple-stripe analysis: `n` records scaled to `im`,
/// of which `collapsed` collapsed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stripe {
    /// Intensity level (> 0).
    pub im: f64,
    /// Number of records run at this level (≥ 1).
    pub n: u32,
    /// Number of them that collapsed (≤ n).
    pub collapsed: u32,
}

/// Maximum-likelihood lognormal fit of collapse capacities (one per record,
/// the IM at which it collapses, e.g. from IDA): the closed form
/// ln θ = mean(ln c), β² = mean((ln c − ln θ)²) (the MLE's 1/n, not 1/(n−1)).
///
/// # Errors
/// Fewer than two capacities, a capacity not positive and finite, or all
/// capacities equal (β = 0).
pub fn fit_capacities(capacities: &[f64]) -> Result<Lognormal, FragilityError> {
    if capacities.len() < 2 {
        return Err(ArgumentError::TooFew {
            function: "fit_capacities",
            what: "capacities",
            needed: 2,
            found: capacities.len(),
        }
        .into());
    }
    if let Some((i, c)) = capacities
        .iter()
        .enumerate()
        .find(|(_, c)| !(c.is_finite() && **c > 0.0))
    {
        return Err(ArgumentError::OutOfRange {
            function: "fit_capacities",
            parameter: "capacities",
            index: Some(i),
            value: *c,
            allowed: "capacities > 0 and finite".to_string(),
        }
        .into());
    }
    let n = capacities.len() as f64;
    let mean = capacities.iter().map(|c| c.ln()).sum::<f64>() / n;
    let var = capacities
        .iter()
        .map(|c| (c.ln() - mean).powi(2))
        .sum::<f64>()
        / n;
    if var <= 0.0 {
        return Err(NoFit::EqualCapacities {
            capacity: capacities[0],
        }
        .into());
    }
    Ok(Lognormal {
        theta: mean.exp(),
        beta: var.sqrt(),
    })
}

/// Validate stripes; the first bad one is named by its index.
fn check_stripes(stripes: &[Stripe]) -> Result<(), FragilityError> {
    if stripes.len() < 2 {
        return Err(ArgumentError::TooFew {
            function: "fit_stripes",
            what: "stripes",
            needed: 2,
            found: stripes.len(),
        }
        .into());
    }
    for (i, s) in stripes.iter().enumerate() {
        if !(s.im.is_finite() && s.im > 0.0) {
            return Err(ArgumentError::StripeIm { index: i, im: s.im }.into());
        }
        if s.n == 0 || s.collapsed > s.n {
            return Err(ArgumentError::StripeCounts {
                index: i,
                collapsed: s.collapsed,
                n: s.n,
            }
            .into());
        }
    }
    Ok(())
}

/// Maximum-likelihood lognormal fit of multiple-stripe counts (Baker 2015,
/// *Earthquake Spectra* 31(1)): maximises the binomial likelihood
/// Π_j C(n_j, z_j) p_j^{z_j} (1 − p_j)^{n_j − z_j}, p_j = Φ(ln(x_j/θ)/β).
///
/// In (a, b) with p = Φ(a + b·ln x) this is a probit regression, whose
/// log-likelihood is concave: Newton's method with a backtracking line
/// search converges from any start, to the unique maximum when it exists.
///
/// # Errors
/// Invalid stripes; no finite maximum: no collapse at all, only collapses,
/// or the stripes separate survival from collapse completely (β → 0); or a
/// fitted curve that falls with the IM (β < 0).
pub fn fit_stripes(stripes: &[Stripe]) -> Result<Lognormal, FragilityError> {
    check_stripes(stripes)?;
    let total: u32 = stripes.iter().map(|s| s.collapsed).sum();
    let runs: u32 = stripes.iter().map(|s| s.n).sum();
    if total == 0 || total == runs {
        return Err(NoFit::AllOrNone {
            collapsed: total,
            runs,
        }
        .into());
    }
    let max_survived = stripes
        .iter()
        .filter(|s| s.collapsed < s.n)
        .map(|s| s.im)
        .fold(f64::NEG_INFINITY, f64::max);
    let min_collapsed = stripes
        .iter()
        .filter(|s| s.collapsed > 0)
        .map(|s| s.im)
        .fold(f64::INFINITY, f64::min);
    if max_survived < min_collapsed {
        return Err(NoFit::Separated {
            max_survived,
            min_collapsed,
        }
        .into());
    }
    // standardised log-IM for conditioning: x = (ln im − m)/s
    let logs: Vec<f64> = stripes.iter().map(|s| s.im.ln()).collect();
    let m = logs.iter().sum::<f64>() / logs.len() as f64;
    let s = (logs.iter().map(|l| (l - m).powi(2)).sum::<f64>() / logs.len() as f64).sqrt();
    if s <= 0.0 {
        return Err(NoFit::SameIm { im: stripes[0].im }.into());
    }
    let x: Vec<f64> = logs.iter().map(|l| (l - m) / s).collect();
    let loglik = |a: f64, b: f64| -> f64 {
        stripes
            .iter()
            .zip(&x)
            .map(|(st, xi)| {
                let eta = a + b * xi;
                let (z, f) = (st.collapsed as f64, (st.n - st.collapsed) as f64);
                // skip zero-count terms: 0·(−∞) would be NaN
                (if z > 0.0 {
                    z * normal::ln_cdf(eta)
                } else {
                    0.0
                }) + (if f > 0.0 {
                    f * normal::ln_cdf(-eta)
                } else {
                    0.0
                })
            })
            .sum()
    };
    let (mut a, mut b) = (0.0f64, 1.0f64);
    let mut ll = loglik(a, b);
    let mut converged = false;
    for _ in 0..200 {
        // gradient and (negative definite) Hessian of the log-likelihood
        let (mut g, mut h) = ([0.0f64; 2], [0.0f64; 3]);
        for (st, xi) in stripes.iter().zip(&x) {
            let eta = a + b * xi;
            let (z, f) = (st.collapsed as f64, (st.n - st.collapsed) as f64);
            let (lp, lm) = (normal::hazard(eta), normal::hazard(-eta));
            let d1 = z * lp - f * lm;
            let d2 = -z * lp * (eta + lp) - f * lm * (lm - eta);
            g[0] += d1;
            g[1] += d1 * xi;
            h[0] += d2;
            h[1] += d2 * xi;
            h[2] += d2 * xi * xi;
        }
        let det = h[0] * h[2] - h[1] * h[1];
        // Newton step −H⁻¹g
        let (da, db) = (
            -(h[2] * g[0] - h[1] * g[1]) / det,
            -(h[0] * g[1] - h[1] * g[0]) / det,
        );
        if !(da.is_finite() && db.is_finite()) {
            break;
        }
        let mut t = 1.0;
        let mut accepted = false;
        for _ in 0..60 {
            let (na, nb) = (a + t * da, b + t * db);
            let nll = loglik(na, nb);
            if nll >= ll - 1e-12 * ll.abs() {
                (a, b, ll) = (na, nb, nll.max(ll));
                accepted = true;
                break;
            }
            t *= 0.5;
        }
        let small =
            (t * da).abs() <= 1e-13 * (1.0 + a.abs()) && (t * db).abs() <= 1e-13 * (1.0 + b.abs());
        if !accepted || small {
            converged = small || (g[0].abs() + g[1].abs()) < 1e-9;
            break;
        }
    }
    if !converged {
        return Err(NoFit::NotConverged.into());
    }
    if b.is_nan() || b <= 0.0 {
        return Err(NoFit::Falling { slope: b }.into());
    }
    Ok(Lognormal {
        theta: (m - a * s / b).exp(),
        beta: s / b,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn capacities_closed_form() {
        let f = fit_capacities(&[1.0, std::f64::consts::E.powi(2)]).unwrap();
        assert!((f.theta - std::f64::consts::E).abs() < 1e-14);
        assert!((f.beta - 1.0).abs() < 1e-14);
        assert!((f.probability(f.theta) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn stripes_at_exact_probabilities_return_the_curve() {
        // counts exactly n·p_j (large n): the MLE is the generating curve
        let truth = Lognormal {
            theta: 0.8,
            beta: 0.5,
        };
        let n = 1_000_000u32;
        let stripes: Vec<Stripe> = [0.3, 0.5, 0.8, 1.2, 2.0]
            .iter()
            .map(|&im| Stripe {
                im,
                n,
                collapsed: (truth.probability(im) * n as f64).round() as u32,
            })
            .collect();
        let f = fit_stripes(&stripes).unwrap();
        assert!((f.theta / truth.theta - 1.0).abs() < 1e-4, "{f:?}");
        assert!((f.beta / truth.beta - 1.0).abs() < 1e-4, "{f:?}");
    }

    #[test]
    fn degenerate_stripes_are_errors() {
        let st = |im, n, collapsed| Stripe { im, n, collapsed };
        let no = fit_stripes(&[st(1.0, 5, 0), st(2.0, 5, 0)]).unwrap_err();
        assert!(no.to_string().contains("0 of 10"), "{no}");
        let sep = fit_stripes(&[st(1.0, 5, 0), st(2.0, 5, 5)]).unwrap_err();
        assert!(sep.to_string().contains("beta -> 0"), "{sep}");
        let bad = fit_stripes(&[st(1.0, 5, 6), st(2.0, 5, 5)]).unwrap_err();
        assert!(bad.to_string().contains("stripes[0]"), "{bad}");
        let nan = fit_stripes(&[st(1.0, 5, 1), st(f64::NAN, 5, 5)]).unwrap_err();
        assert!(nan.to_string().contains("stripes[1].im"), "{nan}");
        let c = fit_capacities(&[1.0, -1.0]).unwrap_err();
        assert!(c.to_string().contains("capacities[1]"), "{c}");
        assert!(fit_capacities(&[1.0]).is_err());
        assert!(fit_capacities(&[2.0, 2.0]).is_err());
    }
}
