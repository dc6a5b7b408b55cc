//! Turns IR into the view models fed to the Tera templates.
//!
//! All text that depends on the IR (expressions, signatures, doc lines) is built here,
//! so the templates only do layout.

mod ground;
pub(crate) mod indices;
mod registry;
mod tape;
pub(crate) mod text;
mod variant;

use serde::Serialize;

pub use ground::render_ground;
pub use registry::render_mod;
pub use text::{camel_case, float_literal};
pub use variant::render_variant;

use crate::{Error, Result};
use text::tidy;

const VARIANT_TEMPLATE: &str = include_str!("../../templates/variant.rs.tera");
const MOD_TEMPLATE: &str = include_str!("../../templates/mod.rs.tera");
const GROUND_TEMPLATE: &str = include_str!("../../templates/ground.rs.tera");

fn tera_for(name: &str, source: &str, origin: &str) -> Result<tera::Tera> {
    let mut tera = tera::Tera::default();
    tera.autoescape_on(Vec::new());
    tera.add_raw_template(name, source)
        .map_err(|e| Error::template(origin, &e))?;
    Ok(tera)
}

pub(crate) fn render_template<T: Serialize>(
    name: &str,
    source: &str,
    view: &T,
    origin: &str,
) -> Result<String> {
    let tera = tera_for(name, source, origin)?;
    let ctx = tera::Context::from_serialize(view).map_err(|e| Error::template(origin, &e))?;
    let text = tera
        .render(name, &ctx)
        .map_err(|e| Error::template(origin, &e))?;
    Ok(tidy(&text))
}
