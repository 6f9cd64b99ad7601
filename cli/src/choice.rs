//! Command-line values of the library's named options ([`strahl::method::Choice`]): listed
//! with their descriptions in `--help`, parsed by name.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use strahl::method::Choice;

/// The parser of an option of type `T`.
pub fn choice<T: Choice + Clone + Send + Sync>() -> impl TypedValueParser<Value = T> {
    choice_among(T::VALUES.iter().map(|&(value, _, _)| value))
}

/// The parser of an option of type `T` that takes only `values`, listed in their order.
pub fn choice_among<T: Choice + Clone + Send + Sync>(
    values: impl IntoIterator<Item = T>,
) -> impl TypedValueParser<Value = T> {
    let values: Vec<PossibleValue> = values
        .into_iter()
        .filter_map(|value| T::VALUES.iter().find(|(v, _, _)| *v == value))
        .map(|&(_, name, help)| PossibleValue::new(name).help(help))
        .collect();
    PossibleValuesParser::new(values).map(|name| match T::from_name(&name) {
        Some(value) => value,
        // The possible-values parser lets through only the names listed above.
        None => unreachable!("'{name}' is one of the listed names"),
    })
}
