//! The check every output passes before it is written: every number in it
//! finite. It walks the value's own `Serialize` form (the JSON contract) with
//! a serializer of its own, so it sees exactly the numbers a reader gets, in
//! every format; a value it cannot walk is an error, never a pass.

use serde::Serialize;
use serde::ser::{self, Impossible};
use std::fmt::Display;

/// Why a value did not pass.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CheckError {
    /// A number is NaN or infinite, at this path (`samples[3].larmor[2]`).
    #[error("the number at {0} is not finite")]
    NonFinite(String),
    /// The value could not be walked (its `Serialize` failed or holds a key
    /// that is not text): the check did not happen.
    #[error("the output could not be checked: {0}")]
    Unchecked(String),
}

impl ser::Error for CheckError {
    fn custom<T: Display>(msg: T) -> Self {
        CheckError::Unchecked(msg.to_string())
    }
}

/// The path of the first number in `value` that is NaN or infinite, if any;
/// an error when the value cannot be walked.
pub fn first_non_finite<T: Serialize + ?Sized>(value: &T) -> Result<Option<String>, CheckError> {
    match value.serialize(Walk {
        path: String::new(),
    }) {
        Ok(()) => Ok(None),
        Err(CheckError::NonFinite(path)) => Ok(Some(path)),
        Err(e) => Err(e),
    }
}

/// `a.b`, or `b` at the root.
fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// The walker at one place in the value.
struct Walk {
    path: String,
}

type Done = Result<(), CheckError>;

impl ser::Serializer for Walk {
    type Ok = ();
    type Error = CheckError;
    type SerializeSeq = Seq;
    type SerializeTuple = Seq;
    type SerializeTupleStruct = Seq;
    type SerializeTupleVariant = Seq;
    type SerializeMap = Map;
    type SerializeStruct = Fields;
    type SerializeStructVariant = Fields;

    fn serialize_f64(self, v: f64) -> Done {
        if v.is_finite() {
            Ok(())
        } else {
            Err(CheckError::NonFinite(self.path))
        }
    }
    fn serialize_f32(self, v: f32) -> Done {
        self.serialize_f64(f64::from(v))
    }
    fn serialize_bool(self, _: bool) -> Done {
        Ok(())
    }
    fn serialize_i8(self, _: i8) -> Done {
        Ok(())
    }
    fn serialize_i16(self, _: i16) -> Done {
        Ok(())
    }
    fn serialize_i32(self, _: i32) -> Done {
        Ok(())
    }
    fn serialize_i64(self, _: i64) -> Done {
        Ok(())
    }
    fn serialize_u8(self, _: u8) -> Done {
        Ok(())
    }
    fn serialize_u16(self, _: u16) -> Done {
        Ok(())
    }
    fn serialize_u32(self, _: u32) -> Done {
        Ok(())
    }
    fn serialize_u64(self, _: u64) -> Done {
        Ok(())
    }
    fn serialize_char(self, _: char) -> Done {
        Ok(())
    }
    fn serialize_str(self, _: &str) -> Done {
        Ok(())
    }
    fn serialize_bytes(self, _: &[u8]) -> Done {
        Ok(())
    }
    fn serialize_none(self) -> Done {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Done {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Done {
        Ok(())
    }
    fn serialize_unit_struct(self, _: &'static str) -> Done {
        Ok(())
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> Done {
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, value: &T) -> Done {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Done {
        value.serialize(Walk {
            path: join(&self.path, variant),
        })
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Seq, CheckError> {
        Ok(Seq {
            path: self.path,
            index: 0,
        })
    }
    fn serialize_tuple(self, _: usize) -> Result<Seq, CheckError> {
        self.serialize_seq(None)
    }
    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Seq, CheckError> {
        self.serialize_seq(None)
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Seq, CheckError> {
        Ok(Seq {
            path: join(&self.path, variant),
            index: 0,
        })
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Map, CheckError> {
        Ok(Map {
            path: self.path,
            key: None,
        })
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Fields, CheckError> {
        Ok(Fields { path: self.path })
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Fields, CheckError> {
        Ok(Fields {
            path: join(&self.path, variant),
        })
    }
}

/// The items of a sequence or tuple, each at `path[i]`.
struct Seq {
    path: String,
    index: usize,
}

impl Seq {
    fn item<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
        let path = format!("{}[{}]", self.path, self.index);
        self.index += 1;
        value.serialize(Walk { path })
    }
}

impl ser::SerializeSeq for Seq {
    type Ok = ();
    type Error = CheckError;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
        self.item(value)
    }
    fn end(self) -> Done {
        Ok(())
    }
}

impl ser::SerializeTuple for Seq {
    type Ok = ();
    type Error = CheckError;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
        self.item(value)
    }
    fn end(self) -> Done {
        Ok(())
    }
}

impl ser::SerializeTupleStruct for Seq {
    type Ok = ();
    type Error = CheckError;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
        self.item(value)
    }
    fn end(self) -> Done {
        Ok(())
    }
}

impl ser::SerializeTupleVariant for Seq {
    type Ok = ();
    type Error = CheckError;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
        self.item(value)
    }
    fn end(self) -> Done {
        Ok(())
    }
}

/// The fields of a struct, each at `path.name`.
struct Fields {
    path: String,
}

impl ser::SerializeStruct for Fields {
    type Ok = ();
    type Error = CheckError;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Done {
        value.serialize(Walk {
            path: join(&self.path, key),
        })
    }
    fn end(self) -> Done {
        Ok(())
    }
}

impl ser::SerializeStructVariant for Fields {
    type Ok = ();
    type Error = CheckError;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Done {
        value.serialize(Walk {
            path: join(&self.path, key),
        })
    }
    fn end(self) -> Done {
        Ok(())
    }
}

/// The entries of a map (and of a struct with flattened fields), each at
/// `path.key`.
struct Map {
    path: String,
    key: Option<String>,
}

impl ser::SerializeMap for Map {
    type Ok = ();
    type Error = CheckError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Done {
        self.key = Some(key.serialize(KeyName)?);
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
        let key = self.key.take().unwrap_or_default();
        value.serialize(Walk {
            path: join(&self.path, &key),
        })
    }
    fn end(self) -> Done {
        Ok(())
    }
}

/// A map key as text; a key that is not text or a whole number is refused.
struct KeyName;

impl ser::Serializer for KeyName {
    type Ok = String;
    type Error = CheckError;
    type SerializeSeq = Impossible<String, CheckError>;
    type SerializeTuple = Impossible<String, CheckError>;
    type SerializeTupleStruct = Impossible<String, CheckError>;
    type SerializeTupleVariant = Impossible<String, CheckError>;
    type SerializeMap = Impossible<String, CheckError>;
    type SerializeStruct = Impossible<String, CheckError>;
    type SerializeStructVariant = Impossible<String, CheckError>;

    fn serialize_str(self, v: &str) -> Result<String, CheckError> {
        Ok(v.to_string())
    }
    fn serialize_char(self, v: char) -> Result<String, CheckError> {
        Ok(v.to_string())
    }
    fn serialize_u64(self, v: u64) -> Result<String, CheckError> {
        Ok(v.to_string())
    }
    fn serialize_i64(self, v: i64) -> Result<String, CheckError> {
        Ok(v.to_string())
    }
    fn serialize_u8(self, v: u8) -> Result<String, CheckError> {
        self.serialize_u64(u64::from(v))
    }
    fn serialize_u16(self, v: u16) -> Result<String, CheckError> {
        self.serialize_u64(u64::from(v))
    }
    fn serialize_u32(self, v: u32) -> Result<String, CheckError> {
        self.serialize_u64(u64::from(v))
    }
    fn serialize_i8(self, v: i8) -> Result<String, CheckError> {
        self.serialize_i64(i64::from(v))
    }
    fn serialize_i16(self, v: i16) -> Result<String, CheckError> {
        self.serialize_i64(i64::from(v))
    }
    fn serialize_i32(self, v: i32) -> Result<String, CheckError> {
        self.serialize_i64(i64::from(v))
    }
    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
    ) -> Result<String, CheckError> {
        Ok(variant.to_string())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<String, CheckError> {
        value.serialize(self)
    }
    fn serialize_bool(self, _: bool) -> Result<String, CheckError> {
        Err(not_text())
    }
    fn serialize_f32(self, _: f32) -> Result<String, CheckError> {
        Err(not_text())
    }
    fn serialize_f64(self, _: f64) -> Result<String, CheckError> {
        Err(not_text())
    }
    fn serialize_bytes(self, _: &[u8]) -> Result<String, CheckError> {
        Err(not_text())
    }
    fn serialize_none(self) -> Result<String, CheckError> {
        Err(not_text())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, _: &T) -> Result<String, CheckError> {
        Err(not_text())
    }
    fn serialize_unit(self) -> Result<String, CheckError> {
        Err(not_text())
    }
    fn serialize_unit_struct(self, _: &'static str) -> Result<String, CheckError> {
        Err(not_text())
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<String, CheckError> {
        Err(not_text())
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Self::SerializeSeq, CheckError> {
        Err(not_text())
    }
    fn serialize_tuple(self, _: usize) -> Result<Self::SerializeTuple, CheckError> {
        Err(not_text())
    }
    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleStruct, CheckError> {
        Err(not_text())
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, CheckError> {
        Err(not_text())
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, CheckError> {
        Err(not_text())
    }
    fn serialize_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStruct, CheckError> {
        Err(not_text())
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, CheckError> {
        Err(not_text())
    }
}

fn not_text() -> CheckError {
    CheckError::Unchecked("a map key is not text".into())
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Serialize;
    use std::collections::BTreeMap;

    #[derive(Serialize)]
    struct Inner {
        larmor: [f64; 3],
        note: Option<f64>,
    }

    #[derive(Serialize)]
    struct Outer {
        t: f64,
        samples: Vec<Inner>,
        #[serde(flatten)]
        extra: BTreeMap<String, f64>,
    }

    #[derive(Serialize)]
    #[serde(untagged)]
    enum Either {
        A(Inner),
    }

    fn sample(x: f64) -> Inner {
        Inner {
            larmor: [0.0, 1.0, x],
            note: None,
        }
    }

    #[test]
    fn the_first_non_finite_number_is_named_by_its_path() {
        let ok = Outer {
            t: 1.0,
            samples: vec![sample(2.0), sample(3.0)],
            extra: BTreeMap::new(),
        };
        assert_eq!(first_non_finite(&ok), Ok(None));
        let bad = Outer {
            samples: vec![sample(2.0), sample(f64::NAN)],
            ..ok
        };
        assert_eq!(
            first_non_finite(&bad),
            Ok(Some("samples[1].larmor[2]".into()))
        );
        let mut extra = BTreeMap::new();
        extra.insert("rate".to_string(), f64::INFINITY);
        let flat = Outer {
            t: 0.0,
            samples: vec![],
            extra,
        };
        assert_eq!(first_non_finite(&flat), Ok(Some("rate".into())));
        let inner = Inner {
            larmor: [0.0; 3],
            note: Some(f64::NEG_INFINITY),
        };
        assert_eq!(first_non_finite(&Either::A(inner)), Ok(Some("note".into())));
        assert_eq!(first_non_finite(&f32::NAN), Ok(Some(String::new())));
    }

    /// A value the walker cannot follow fails the check loudly instead of
    /// passing it (the old check converted to TOML and passed on failure).
    #[test]
    fn a_value_that_cannot_be_walked_is_an_error_not_a_pass() {
        struct Broken;
        impl Serialize for Broken {
            fn serialize<S: ser::Serializer>(&self, _: S) -> Result<S::Ok, S::Error> {
                Err(ser::Error::custom("no form"))
            }
        }
        assert_eq!(
            first_non_finite(&Broken),
            Err(CheckError::Unchecked("no form".into()))
        );
        let mut by_number: BTreeMap<(u8, u8), f64> = BTreeMap::new();
        by_number.insert((1, 2), 1.0);
        assert!(matches!(
            first_non_finite(&by_number),
            Err(CheckError::Unchecked(_))
        ));
        // A None inside an array is fine (TOML could not hold it).
        assert_eq!(first_non_finite(&vec![None, Some(1.0)]), Ok(None));
    }
}
