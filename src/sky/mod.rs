//! The sun and the sky over a site: the sun's position from date, time and place by NREL's
//! Solar Position Algorithm ([`sun_position`]), the 15 CIE standard general skies as sky
//! luminance distributions ([`CieSky`], [`relative_luminance`]) scaled to a diffuse
//! horizontal irradiance, and a tabulated sky ([`SkyTable`]) to sample directions in
//! proportion to `L·cos θ` and to evaluate the density of that sampling.
//!
//! Pure functions of their inputs in `f64`; nothing here knows a scene or a renderer.
//!
//! # Conventions
//!
//! strahl's world frame is right-handed with **y up**; for the sun and the sky, **−z is
//! north and +x is east** (so +z is south). Directions are unit vectors pointing *away from*
//! the observer: toward the sun, toward a sky element. Angles in the public API are in
//! degrees where they describe the sun's position (zenith angle from +y, azimuth clockwise
//! from north toward east, as NREL and CIE give them; [`direction_from_angles`] turns them
//! into a vector) and radiance is per steradian (W·m⁻²·sr⁻¹ when irradiance is given in
//! W·m⁻², cd·m⁻² when illuminance is given in lux).

mod cie;
mod direction;
mod sun;
mod table;

pub use cie::{CieParameters, CieSky, CieSkyType, relative_luminance};
pub use direction::{angles_from_direction, direction_from_angles};
pub use sun::{
    DEFAULT_DELTA_T_S, LocalTime, Observer, SOLAR_CONSTANT, STANDARD_PRESSURE_MBAR,
    STANDARD_TEMPERATURE_C, SUNRISE_REFRACTION_DEG, SunPosition, sun_position,
};
pub use table::{SkySample, SkyTable};
