//! clap's value parsers over the core's name tables: the names a flag
//! accepts, and the help line of each, are the core's (one table for the
//! flag, the scene key and the live view), never restated here.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use spintop::output::Format;
use spintop::sim::MethodChoice;

/// `--method NAME`: the names of [`MethodChoice::NAMES`].
pub fn method() -> impl TypedValueParser<Value = MethodChoice> {
    PossibleValuesParser::new(
        MethodChoice::ALL.map(|m| PossibleValue::new(m.name()).help(m.help())),
    )
    .map(|name| MethodChoice::from_name(&name).unwrap_or(MethodChoice::Auto))
}

/// `--format NAME`: the names of [`Format::NAMES`].
pub fn format() -> impl TypedValueParser<Value = Format> {
    PossibleValuesParser::new(Format::ALL.map(|f| PossibleValue::new(f.name()).help(f.help())))
        .map(|name| Format::from_name(&name).unwrap_or(Format::Table))
}
