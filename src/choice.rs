//! Options with a fixed set of named values (an accelerator, a tone mapper, an iteration
//! scheme, …): each value has a name, used on command lines and in files, and a one-line
//! description. The library knows nothing of any command-line parser; a front end lists and
//! parses the values through [`Choice`].

/// An option whose values have names.
pub trait Choice: Copy + PartialEq + Sized + 'static {
    /// Every value with its name and a one-line description, in the order to list them.
    const VALUES: &'static [(Self, &'static str, &'static str)];

    /// The name of this value.
    fn name(self) -> &'static str;

    /// The value called `name`, if any.
    fn from_name(name: &str) -> Option<Self> {
        Self::VALUES
            .iter()
            .find(|(_, n, _)| *n == name)
            .map(|&(value, _, _)| value)
    }
}

/// A name that is not one of an option's values.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("'{given}' is not one of: {}", .expected.join(", "))]
pub struct UnknownName {
    /// The name given.
    pub given: String,
    /// The names the option has.
    pub expected: Vec<&'static str>,
}

/// Parses `name` as a value of `T`.
pub fn parse<T: Choice>(name: &str) -> Result<T, UnknownName> {
    T::from_name(name).ok_or_else(|| UnknownName {
        given: name.to_string(),
        expected: T::VALUES.iter().map(|&(_, n, _)| n).collect(),
    })
}

/// Implements [`Choice`], `Display` and `FromStr` for an enum of unit variants from one list
/// of `Variant = "name", "description";` entries (the `match` in `name` makes the compiler
/// check that every variant is listed).
macro_rules! named_values {
    ($ty:ty { $($value:path = $name:literal, $help:literal;)+ }) => {
        impl $crate::choice::Choice for $ty {
            const VALUES: &'static [($ty, &'static str, &'static str)] =
                &[$(($value, $name, $help)),+];

            fn name(self) -> &'static str {
                match self {
                    $($value => $name),+
                }
            }
        }

        impl ::std::fmt::Display for $ty {
            fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                f.write_str($crate::choice::Choice::name(*self))
            }
        }

        impl ::std::str::FromStr for $ty {
            type Err = $crate::choice::UnknownName;

            fn from_str(s: &str) -> Result<Self, Self::Err> {
                $crate::choice::parse(s)
            }
        }
    };
}

pub(crate) use named_values;

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Clone, Copy, Debug, PartialEq)]
    enum Fruit {
        Apple,
        Pear,
    }

    named_values!(Fruit {
        Fruit::Apple = "apple", "A round fruit.";
        Fruit::Pear = "pear", "A pear-shaped fruit.";
    });

    #[test]
    fn names_parse_and_print_both_ways() {
        assert_eq!("pear".parse(), Ok(Fruit::Pear));
        assert_eq!(Fruit::Apple.to_string(), "apple");
        let e = "plum".parse::<Fruit>().unwrap_err();
        assert_eq!(e.to_string(), "'plum' is not one of: apple, pear");
        assert_eq!(Fruit::VALUES.len(), 2);
    }
}
