//! The units of a record, in one place: the units model (what one unit of a record's samples is
//! for a structure), and the unit expressions headers write (`CM/SEC/SEC`, `m/s^2`, `gal`, `G`,
//! `20 MSEC`), read as expressions of a length and a time rather than matched as substrings, so
//! that `G (1 G = 980.665 CM/SEC/SEC)` is g and `KM/S/S` is not taken for m/s².

/// The acceleration unit of a record's samples.
///
/// **The units model.** An absolute unit (cm/s², m/s²) is physical: the record's accelerations
/// are the same whatever the structure's g. A record in g is felt as the structure's g: one unit
/// is g of the structure (its `g`, or standard gravity [`STANDARD_GRAVITY`](crate::STANDARD_GRAVITY)
/// when a scene does not set one), so the same file moves a block on the Moon and on Earth alike
/// relative to its weight. [`AccelUnit::in_model_units`] is the only place that applies it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AccelUnit {
    /// Multiples of the structure's g.
    G,
    /// cm/s² (gal).
    CmPerS2,
    /// m/s².
    MPerS2,
}

impl AccelUnit {
    /// Every unit, in the order of [`AccelUnit::NAMES`].
    pub const ALL: [AccelUnit; 3] = [AccelUnit::G, AccelUnit::CmPerS2, AccelUnit::MPerS2];
    /// The names accepted by [`AccelUnit::parse`] (first spelling of each unit).
    pub const NAMES: [&'static str; 3] = ["g", "cm/s2", "m/s2"];

    /// One unit of this acceleration in a structure's units, where `g_model` is the structure's g
    /// in its own units and `g_si` the same g in m/s²: g itself for a record in g, the absolute
    /// value (m/s² × `g_model / g_si`) for an absolute unit. For a structure in SI units
    /// (`g_model == g_si`) an absolute unit converts exactly (m/s² → 1, cm/s² → 0.01).
    pub fn in_model_units(self, g_model: f64, g_si: f64) -> f64 {
        let per_m_s2 = g_model / g_si;
        match self {
            AccelUnit::G => g_model,
            AccelUnit::CmPerS2 => 0.01 * per_m_s2,
            AccelUnit::MPerS2 => per_m_s2,
        }
    }

    /// One unit of this acceleration in m/s², for a structure whose g is `g_si` m/s².
    pub fn in_m_s2(self, g_si: f64) -> f64 {
        self.in_model_units(g_si, g_si)
    }

    /// The short name (`g`, `cm/s2`, `m/s2`).
    pub fn name(self) -> &'static str {
        match self {
            AccelUnit::G => "g",
            AccelUnit::CmPerS2 => "cm/s2",
            AccelUnit::MPerS2 => "m/s2",
        }
    }

    /// The unit as a message prints it (`g`, `cm/s²`, `m/s²`).
    pub fn symbol(self) -> &'static str {
        match self {
            AccelUnit::G => "g",
            AccelUnit::CmPerS2 => "cm/s²",
            AccelUnit::MPerS2 => "m/s²",
        }
    }

    /// A unit as a user writes it: `g`, `cm/s2` (`cm/s^2`, `cm/sec/sec`, `gal`, ...), `m/s2`
    /// (`m/s^2`, `m/s/s`, ...); case and spaces ignored. The same expressions the headers use.
    pub fn parse(s: &str) -> Option<AccelUnit> {
        match unit_expression(s) {
            Some(Quantity::Accel(u)) => Some(u),
            _ => None,
        }
    }
}

/// What a unit expression measures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Quantity {
    /// An acceleration in a unit the readers convert.
    Accel(AccelUnit),
    /// An acceleration in another unit: m/s² per unit (`KM/S/S`, `FT/S/S`, `MM/S^2`).
    OtherAccel(f64),
    /// A velocity (`CM/SEC`, `kine`).
    Velocity,
    /// A length (a displacement history).
    Displacement,
    /// A time: seconds per unit (`SEC`, `MSEC`).
    Time(f64),
}

/// Lengths and times a unit expression is made of: (spellings, metres or seconds per unit).
const LENGTHS: [(&[&str], f64); 6] = [
    (&["M", "METER", "METERS", "METRE", "METRES"], 1.0),
    (&["CM"], 0.01),
    (&["MM"], 0.001),
    (&["KM"], 1000.0),
    (&["FT"], 0.3048),
    (&["IN"], 0.0254),
];
const TIMES: [(&[&str], f64); 2] = [
    (&["S", "SEC", "SECS", "SECOND", "SECONDS"], 1.0),
    (
        &["MS", "MSEC", "MSECS", "MILLISECOND", "MILLISECONDS"],
        0.001,
    ),
];

/// Reads a unit expression: `G`; `GAL`; `KINE`; or a length over times, each with an optional
/// power (`CM/SEC/SEC`, `M/S^2`, `CM/S**2`, `M/S2`, `m/s²`); a time alone (`SEC`, `MSEC`). Case
/// and spaces are ignored. `None` when it is none of these.
pub(crate) fn unit_expression(s: &str) -> Option<Quantity> {
    let e: String = s
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_uppercase()
        .replace('²', "^2");
    match e.as_str() {
        "G" => return Some(Quantity::Accel(AccelUnit::G)),
        "GAL" | "GALS" => return Some(Quantity::Accel(AccelUnit::CmPerS2)),
        "KINE" => return Some(Quantity::Velocity),
        _ => {}
    }
    // Powers of a length and of a time, and the SI value of one unit.
    let (mut length, mut time, mut si) = (0i32, 0i32, 1.0f64);
    for (k, term) in e.split('/').enumerate() {
        let (name, power) = power_of(term)?;
        let sign = if k == 0 { 1 } else { -1 };
        let find = |table: &[(&[&str], f64)]| {
            table
                .iter()
                .find(|(names, _)| names.contains(&name))
                .map(|&(_, v)| v)
        };
        if let Some(v) = find(&LENGTHS) {
            length += sign * power;
            si *= v.powi(sign * power);
        } else if let Some(v) = find(&TIMES) {
            time += sign * power;
            si *= v.powi(sign * power);
        } else {
            return None;
        }
    }
    Some(match (length, time) {
        (1, -2) if si == 1.0 => Quantity::Accel(AccelUnit::MPerS2),
        (1, -2) if si == 0.01 => Quantity::Accel(AccelUnit::CmPerS2),
        (1, -2) => Quantity::OtherAccel(si),
        (1, -1) => Quantity::Velocity,
        (1, 0) => Quantity::Displacement,
        (0, 1) => Quantity::Time(si),
        _ => return None,
    })
}

/// A unit name and its power: `S^2`, `S**2`, `S2`, `S^-1`, `S`.
fn power_of(term: &str) -> Option<(&str, i32)> {
    let name_len = term
        .find(|c: char| !c.is_ascii_alphabetic())
        .unwrap_or(term.len());
    let (name, rest) = term.split_at(name_len);
    if name.is_empty() {
        return None;
    }
    let digits = rest
        .strip_prefix("**")
        .or_else(|| rest.strip_prefix('^'))
        .unwrap_or(rest);
    let power = if digits.is_empty() {
        1
    } else {
        digits
            .parse::<i32>()
            .ok()
            .filter(|p| (-4..=4).contains(p))?
    };
    Some((name, power))
}

/// What a header line says about the quantity and its unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Declared {
    /// No unit stated (the samples are taken as g unless the user states one).
    Nothing,
    /// An acceleration unit.
    Unit(AccelUnit),
    /// An acceleration in a unit the readers do not convert (m/s² per unit), or a unit they
    /// cannot read (`None`).
    Unknown(Option<f64>),
    /// A velocity or displacement history.
    NotAcceleration,
}

impl Declared {
    fn of(q: Option<Quantity>) -> Declared {
        match q {
            Some(Quantity::Accel(u)) => Declared::Unit(u),
            Some(Quantity::OtherAccel(si)) => Declared::Unknown(Some(si)),
            Some(Quantity::Velocity | Quantity::Displacement) => Declared::NotAcceleration,
            Some(Quantity::Time(_)) | None => Declared::Unknown(None),
        }
    }
}

/// Reads the quantity and the unit from a header line as the databases write it: the unit is the
/// expression after `UNITS OF`, `UNITS ARE`, `UNITS:` (`ACCELERATION TIME SERIES IN UNITS OF
/// G`, `The units are (g)`, `UNITS: g (9.81 m/s/s)`), else an expression after `IN`
/// (`accel. in gal`) or one with a `/`; what follows it (a parenthesis explaining g, filter
/// points) is not read. A line naming a velocity or displacement is refused as such.
pub(crate) fn declared_unit(line: &str) -> Declared {
    let up = line
        .to_ascii_uppercase()
        .replace(':', " : ")
        .replace('=', " = ")
        .replace(" /", "/")
        .replace("/ ", "/")
        .replace(" ^", "^")
        .replace("^ ", "^");
    let clean = |w: &str| {
        w.trim_start_matches(['(', '['])
            .trim_end_matches([')', ']', ',', ';', '.'])
            .to_owned()
    };
    let words: Vec<String> = up.split_whitespace().map(clean).collect();
    if words.iter().any(|w| w == "VELOCITY" || w == "DISPLACEMENT") {
        return Declared::NotAcceleration;
    }
    // `UNITS OF x`, `UNITS ARE x`, `UNITS: x`, `UNITS x` where x is a unit.
    let filler = ["OF", "ARE", "IS", "IN", ":", "="];
    for (i, w) in words.iter().enumerate() {
        if w != "UNITS" && w != "UNIT" {
            continue;
        }
        let rest = &words[i + 1..];
        let introduced = rest.first().is_some_and(|n| filler.contains(&n.as_str()));
        let at = rest.iter().position(|w| !filler.contains(&w.as_str()));
        match at.map(|j| (&rest[j], &rest[j + 1..])) {
            Some((u, after)) if introduced || unit_expression(u).is_some() => {
                return scaled(Declared::of(unit_expression(u)), after)
            }
            _ => {}
        }
    }
    for (k, w) in words.iter().enumerate() {
        let after_in = k > 0 && words[k - 1] == "IN";
        let q = unit_expression(w);
        let named = w.contains('/') || matches!(w.as_str(), "GAL" | "GALS" | "KINE");
        if named
            && matches!(
                q,
                Some(Quantity::Accel(_) | Quantity::OtherAccel(_) | Quantity::Velocity)
            )
        {
            return scaled(Declared::of(q), &words[k + 1..]);
        }
        // What follows `IN` is the unit: an acceleration is read; `IN %G`, `IN MG`, `IN 0.001 G`,
        // `IN FEET/SEC/SEC`, `IN MGAL`, `IN COUNTS`, a time (`IN SEC`) are refused as units the
        // readers do not know, and a velocity or length (`IN CM/SEC`, `IN CM`) as not an
        // acceleration: never passed over and the samples read as g (`ACCELERATION IN CM`
        // was).
        if after_in && !matches!(w.as_str(), "UNITS" | "UNIT" | "THE") {
            return scaled(Declared::of(q), &words[k + 1..]);
        }
        // A bracketed unit-like word: `(MG)`, `(%G)`.
        if matches!(
            w.as_str(),
            "MG" | "%G" | "MGAL" | "MILLIG" | "MILLI-G" | "COUNTS"
        ) {
            return Declared::Unknown(None);
        }
    }
    Declared::Nothing
}

/// A unit followed by a multiplier (`G X 10^-3`, `G x1000`, `G ×1000`, `G (SCALED BY 1000)`,
/// `CM/SEC/SEC TIMES 10`, `m/s2 * 100`) is refused: applying it needs its direction, which
/// the line does not say reliably, and dropping it is 10-1000x wrong.
fn scaled(unit: Declared, after: &[String]) -> Declared {
    let multiplier = after.iter().take(3).any(|w| {
        matches!(
            w.as_str(),
            "X" | "×" | "TIMES" | "*" | "SCALED" | "MULTIPLIED" | "FACTOR"
        ) || w.starts_with('*')
            || w.strip_prefix(['X', '×'])
                .is_some_and(|r| r.starts_with(|c: char| c.is_ascii_digit()))
    });
    match unit {
        Declared::Unit(_) | Declared::Unknown(Some(_)) if multiplier => Declared::Unknown(None),
        u => u,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit line that names a unit the readers do not know, or a multiplier after a unit, is
    /// refused, never read as g or as the bare unit (issue 47: 100x, 1000x or 32x too strong).
    #[test]
    fn unknown_units_and_multipliers_are_refused() {
        for line in [
            "ACCELERATION IN %G",
            "ACCELERATION IN MG",
            "ACCELERATION (MG)",
            "ACCELERATION IN 0.001 G",
            "ACCELERATION IN FEET/SEC/SEC",
            "ACCELERATION IN MGAL",
            "ACCELERATION IN COUNTS",
            "ACCELERATION IN UNITS OF G X 10^-3",
            "ACCELERATION IN UNITS OF G x1000",
            "ACCELERATION IN UNITS OF G (SCALED BY 1000)",
            "ACCELERATION IN CM/SEC/SEC TIMES 10",
            "UNITS: m/s2 * 100",
            "ACCELERATION IN UNITS OF G ×1000",
            "ACCELERATION IN UNITS OF G × 10^-3",
        ] {
            assert!(
                matches!(declared_unit(line), Declared::Unknown(_)),
                "{line}: {:?}",
                declared_unit(line)
            );
        }
        for (line, unit) in [
            ("ACCELERATION TIME SERIES IN UNITS OF G", AccelUnit::G),
            ("UNITS: g (9.81 m/s/s)", AccelUnit::G),
            ("ACCELERATION IN CM/SEC/SEC", AccelUnit::CmPerS2),
            ("accel. in gal", AccelUnit::CmPerS2),
        ] {
            assert!(
                matches!(declared_unit(line), Declared::Unit(u) if u == unit),
                "{line}: {:?}",
                declared_unit(line)
            );
        }
    }

    /// The spellings of K-NET's scale-factor bracket (`3920(cm/s2)/6182761`) are acceleration
    /// units on every reader's unit line too: K-NET refused `cm/s2` because its reader split the
    /// scale factor at the unit's own `/` (fixed there), not because of these rules.
    #[test]
    fn scale_factor_spellings_on_unit_lines() {
        for u in [
            "cm/s2", "cm/s^2", "cm/s/s", "gal", "Gal", "CM/S2", "cm/sec2",
        ] {
            for line in [
                format!("UNITS: {u}"),
                format!("ACCELERATION IN {u}"),
                format!("ACCELERATION TIME SERIES IN UNITS OF {u}"),
            ] {
                assert_eq!(
                    declared_unit(&line),
                    Declared::Unit(AccelUnit::CmPerS2),
                    "{line}"
                );
            }
        }
        for line in [
            "UNITS: m/s2",
            "ACCELERATION (M/S2)",
            "ACCELERATION IN m/s^2",
        ] {
            assert_eq!(
                declared_unit(line),
                Declared::Unit(AccelUnit::MPerS2),
                "{line}"
            );
        }
        for line in [
            "UNITS: cm/s",
            "UNITS: kine",
            "UNITS: cm",
            "ACCELERATION IN CM/S",
        ] {
            assert_eq!(declared_unit(line), Declared::NotAcceleration, "{line}");
        }
    }

    #[test]
    fn expressions() {
        use Quantity::*;
        let cm = Accel(AccelUnit::CmPerS2);
        let m = Accel(AccelUnit::MPerS2);
        for (e, want) in [
            ("G", Some(Accel(AccelUnit::G))),
            ("g", Some(Accel(AccelUnit::G))),
            ("gal", Some(cm)),
            ("CM/SEC/SEC", Some(cm)),
            ("cm/s^2", Some(cm)),
            ("CM/S**2", Some(cm)),
            ("cm/s2", Some(cm)),
            ("cm / s ²", Some(cm)),
            ("M/S/S", Some(m)),
            ("m/sec^2", Some(m)),
            ("KM/S/S", Some(OtherAccel(1000.0))),
            ("MM/S^2", Some(OtherAccel(0.001))),
            ("FT/S/S", Some(OtherAccel(0.3048))),
            ("CM/SEC", Some(Velocity)),
            ("kine", Some(Velocity)),
            ("CM", Some(Displacement)),
            ("SEC", Some(Time(1.0))),
            ("MSEC", Some(Time(0.001))),
            ("GALILEO", None),
            ("S/CM", None),
            ("M/S^9", None),
            ("", None),
            ("/", None),
            ("8F10.5", None),
        ] {
            assert_eq!(unit_expression(e), want, "{e}");
        }
    }

    #[test]
    fn header_lines() {
        use Declared::*;
        let g = Unit(AccelUnit::G);
        let cm = Unit(AccelUnit::CmPerS2);
        let m = Unit(AccelUnit::MPerS2);
        for (line, want) in [
            (
                "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.2 Hz LP=25.0 Hz",
                g,
            ),
            ("ACCELERATION TIME SERIES IN UNITS OF G", g),
            ("The units are (g)", g),
            (
                "ACCELERATION TIME SERIES IN UNITS OF G (1 G = 980.665 CM/SEC/SEC)",
                g,
            ),
            ("UNITS: g (9.81 m/s/s)", g),
            ("ACCELERATION TIME HISTORY IN UNITS OF CM/SEC/SEC", cm),
            ("ACCELERATION IN UNITS OF CM/S^2", cm),
            ("accel. in gal", cm),
            ("UNITS: cm/s^2", cm),
            ("ACCELERATION TIME HISTORY IN UNITS OF M/S/S", m),
            ("ACCELERATION IN M/S^2", m),
            ("ACCELERATION (M / S / S)", m),
            ("units", Nothing),
            ("U", Nothing),
            ("no unit here", Nothing),
            ("UNITS (CM/S/S)", cm),
            (
                "1559 points at equal spacing of 0.02 sec in the format of 8F10.5",
                Nothing,
            ),
            ("ACCELERATION IN UNITS OF KM/S/S", Unknown(Some(1000.0))),
            ("ACCELERATION IN UNITS OF FT/S/S", Unknown(Some(0.3048))),
            ("ACCELERATION IN UNITS OF GALILEO", Unknown(None)),
            ("ACCELERATION IN MM/S/S", Unknown(Some(0.001))),
            ("VELOCITY TIME HISTORY IN UNITS OF CM/SEC", NotAcceleration),
            ("DISPLACEMENT TIME HISTORY IN UNITS OF CM", NotAcceleration),
            ("UNITS: cm/s", NotAcceleration),
            // after IN, a length or a time is no acceleration unit (was: no unit, read as g)
            ("ACCELERATION IN CM", NotAcceleration),
            ("ACCELERATION IN M", NotAcceleration),
            ("ACCELERATION IN SEC", Unknown(None)),
        ] {
            assert_eq!(declared_unit(line), want, "{line}");
        }
    }

    #[test]
    fn user_spellings_and_the_model() {
        for (name, u) in AccelUnit::NAMES.iter().zip(AccelUnit::ALL) {
            assert_eq!(AccelUnit::parse(name), Some(u));
            assert_eq!(u.name(), *name);
        }
        assert_eq!(AccelUnit::parse("CM/S^2"), Some(AccelUnit::CmPerS2));
        assert_eq!(AccelUnit::parse("ft/s2"), None);
        assert_eq!(AccelUnit::parse("cm/s"), None);
        // An absolute unit keeps its value at any g; g follows the structure's.
        for g in [1.62, 9.80665, 9.81, 20.0] {
            assert_eq!(AccelUnit::MPerS2.in_m_s2(g), 1.0);
            assert_eq!(AccelUnit::CmPerS2.in_m_s2(g), 0.01);
            assert_eq!(AccelUnit::G.in_m_s2(g), g);
            // dimensionless (g = 1 model unit): one m/s² is 1/g of the structure's g
            assert_eq!(AccelUnit::MPerS2.in_model_units(1.0, g), 1.0 / g);
            assert_eq!(AccelUnit::G.in_model_units(1.0, g), 1.0);
        }
    }
}
