//! A cell of a sweep: its values, its class (the paper's spectrum regions) and its run or failure.

use rocking::Summary;

/// What happened in a cell (the paper's spectrum regions).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CellClass {
    /// The base never uplifted.
    NoUplift,
    /// It rocked and came back (max θ/α tells how far).
    Survived,
    /// It overturned before any impact.
    OverturnedNoImpact,
    /// It overturned after exactly one impact.
    OverturnedOneImpact,
    /// It overturned after two or more impacts.
    OverturnedImpacts,
    /// The run left the model's validity: its mass matrix became singular, which happens when
    /// the column's deflection carries a top mass over the pivot (a deflection of the order of
    /// the base half-width, far beyond small deformations). The cell has no values; the message
    /// (when, how far) is in the sweep's outcome.
    BeyondModel,
    /// The simulation failed for another reason; the message is in the sweep's outcome. The
    /// other cells are unaffected.
    Failed,
}

impl CellClass {
    /// Every class, in the order of the enum (the order of legends and counts).
    pub const ALL: [CellClass; 7] = [
        CellClass::NoUplift,
        CellClass::Survived,
        CellClass::OverturnedNoImpact,
        CellClass::OverturnedOneImpact,
        CellClass::OverturnedImpacts,
        CellClass::BeyondModel,
        CellClass::Failed,
    ];

    /// The name used in `cells.csv`.
    pub fn as_str(self) -> &'static str {
        match self {
            CellClass::NoUplift => "no-uplift",
            CellClass::Survived => "survived",
            CellClass::OverturnedNoImpact => "overturned-no-impact",
            CellClass::OverturnedOneImpact => "overturned-one-impact",
            CellClass::OverturnedImpacts => "overturned-impacts",
            CellClass::BeyondModel => "beyond-model",
            CellClass::Failed => "failed",
        }
    }

    /// Whether the cell has a result (class, max θ/α, impacts, reported values): every class
    /// but [`CellClass::BeyondModel`] and [`CellClass::Failed`].
    pub fn has_result(self) -> bool {
        !matches!(self, CellClass::BeyondModel | CellClass::Failed)
    }

    /// Whether the structure overturned; `None` for a cell without a result (neither).
    pub fn overturned(self) -> Option<bool> {
        match self {
            CellClass::OverturnedNoImpact
            | CellClass::OverturnedOneImpact
            | CellClass::OverturnedImpacts => Some(true),
            CellClass::NoUplift | CellClass::Survived => Some(false),
            CellClass::BeyondModel | CellClass::Failed => None,
        }
    }

    /// Inverse of [`CellClass::as_str`].
    pub fn parse(s: &str) -> Option<CellClass> {
        CellClass::ALL.into_iter().find(|c| c.as_str() == s)
    }

    /// The class of a finished run.
    pub fn of(summary: &Summary) -> CellClass {
        match (
            summary.overturned,
            summary.impacts,
            summary.first_uplift_time.is_some(),
        ) {
            (true, 0, _) => CellClass::OverturnedNoImpact,
            (true, 1, _) => CellClass::OverturnedOneImpact,
            (true, _, _) => CellClass::OverturnedImpacts,
            (false, _, false) => CellClass::NoUplift,
            (false, _, true) => CellClass::Survived,
        }
    }
}

/// The O(1) result of one cell.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    /// Cell index in sweep order.
    pub index: usize,
    /// Class.
    pub class: CellClass,
    /// max |θ|/α.
    pub max_theta_over_alpha: f64,
    /// Number of impacts.
    pub impacts: u64,
    /// The values of the sweep's reported quantities ([`Sweep::reported`]), in order: `None`
    /// where the cell's run has none (a time of an event that did not happen).
    pub reported: Vec<Option<f64>>,
}

/// What the run of one cell gives the sweep: its summary (for the class, max θ/α and impacts)
/// and the values of the sweep's reported quantities.
#[derive(Clone, Debug, PartialEq)]
pub struct CellRun {
    /// The run's summary.
    pub summary: Summary,
    /// The values of [`Sweep::reported`], in order (`None`: the run has no value).
    pub reported: Vec<Option<f64>>,
}

impl From<Summary> for CellRun {
    fn from(summary: Summary) -> Self {
        CellRun {
            summary,
            reported: Vec::new(),
        }
    }
}

/// A cell without a result: its class ([`CellClass::BeyondModel`] or [`CellClass::Failed`]) and
/// the message the sweep keeps for it. A plain message is a failure.
#[derive(Clone, Debug, PartialEq)]
pub struct CellFailure {
    /// The class the cell gets.
    pub class: CellClass,
    /// Why (kept in the journal and the sweep's outcome).
    pub message: String,
}

impl From<String> for CellFailure {
    fn from(message: String) -> Self {
        CellFailure {
            class: CellClass::Failed,
            message,
        }
    }
}
