//! Tone-mapping options shared by `render` (PNG output) and `solve --export` (vertex colours).

use super::choice::choice;
use clap::Args;
use strahl::image::{ToneMap, ToneMapping};

/// How linear radiance becomes display colour.
#[derive(Debug, Args)]
pub struct ToneArgs {
    /// Tone mapping for 8-bit output and exported vertex colours.
    #[arg(long, value_parser = choice::<ToneMap>(), default_value_t = ToneMap::Auto)]
    pub tonemap: ToneMap,
    /// Exposure in stops applied before tone mapping.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = super::limits::finite::<f32>)]
    pub exposure: f32,
}

impl ToneArgs {
    /// The tone mapping these options ask for.
    pub fn mapping(&self) -> ToneMapping {
        ToneMapping {
            operator: self.tonemap,
            exposure_ev: self.exposure,
        }
    }
}
