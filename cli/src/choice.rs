//! Command-line values of the library's named options ([`strahl::choice::Choice`]): listed
//! with their descriptions in `--help`, parsed by name.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use strahl::choice::Choice;

/// The parser of an option of type `T`.
pub fn choice<T: Choice + Clone + Send + Sync>() -> impl TypedValueParser<Value = T> {
    let values = T::VALUES
        .iter()
        .map(|&(_, name, help)| PossibleValue::new(name).help(help));
    PossibleValuesParser::new(values).map(|name| match T::from_name(&name) {
        Some(value) => value,
        // The possible-values parser lets through only the names listed above.
        None => unreachable!("'{name}' is one of the listed names"),
    })
}
