//! The CIE standard general sky (CIE S 011/E:2003, ISO 15469:2004): 15 relative sky
//! luminance distributions, each a gradation function of the zenith angle times a
//! scattering indicatrix of the angle to the Sun, and their scale from a diffuse horizontal
//! irradiance.

mod luminance;
mod parameters;
mod quadrature;
#[cfg(test)]
mod reference;
mod sky;

pub use luminance::relative_luminance;
pub use parameters::{CieParameters, CieSkyType};
pub use sky::CieSky;
