//! The field types requests are made of: each checks its own rule while it is read (one
//! wording per rule) and describes itself to the JSON Schema, so that a rule and its schema
//! cannot drift apart. A rule that ties two fields together is a request's
//! [`Request::check`](super::Request::check).

use super::ProtoError;
use aesthetic_curves::Point;
use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::Deserialize;
use std::borrow::Cow;
use std::fmt;

/// A point `[x, y]`: two finite numbers (JSON has no others).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Xy(pub Point);

impl<'de> Deserialize<'de> for Xy {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Xy;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("an [x, y] pair of numbers")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Xy, A::Error> {
                let x: f64 = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::invalid_length(0, &self))?;
                let y: f64 = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::invalid_length(1, &self))?;
                if seq.next_element::<de::IgnoredAny>()?.is_some() {
                    return Err(de::Error::invalid_length(3, &self));
                }
                Ok(Xy(Point::new(x, y)))
            }
        }
        d.deserialize_seq(V)
    }
}

impl JsonSchema for Xy {
    fn inline_schema() -> bool {
        true
    }
    fn schema_name() -> Cow<'static, str> {
        "Point".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "A point [x, y].",
            "type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2
        })
    }
}

/// `[x, y]` points, from `MIN` to `MAX` of them (the count is checked before the points
/// are read).
#[derive(Debug, Clone, PartialEq)]
pub struct Points<const MIN: usize, const MAX: usize>(pub Vec<Point>);

/// The message of a count outside `min..=max`.
pub fn count_message(min: usize, max: usize, got: usize) -> String {
    if min == max {
        return format!("needs {min} points, got {got}");
    }
    format!("needs {min} to {max} points, got {got}")
}

/// The items of a sequence, `min` to `max` of them: more than `max` is refused before the
/// items are read (the length a JSON array announces) or as soon as one is too many; `too`
/// says what is wrong for a count.
pub fn bounded_seq<'de, A: SeqAccess<'de>, T: Deserialize<'de>>(
    mut seq: A,
    (min, max): (usize, usize),
    too: impl Fn(usize) -> String,
) -> Result<Vec<T>, A::Error> {
    let hint = seq.size_hint().unwrap_or(0);
    if hint > max {
        return Err(de::Error::custom(too(hint)));
    }
    let mut out = Vec::with_capacity(hint);
    while let Some(x) = seq.next_element()? {
        if out.len() == max {
            return Err(de::Error::custom(too(max + 1)));
        }
        out.push(x);
    }
    if out.len() < min {
        return Err(de::Error::custom(too(out.len())));
    }
    Ok(out)
}

/// `invalid_input` on `field` unless there is one weight per control point.
pub fn check_weight_count(field: &str, points: usize, weights: usize) -> Result<(), ProtoError> {
    if weights == points {
        return Ok(());
    }
    Err(ProtoError::invalid(
        field,
        format!("needs {points} numbers (one per control point), got {weights}"),
    ))
}

impl<'de, const MIN: usize, const MAX: usize> Deserialize<'de> for Points<MIN, MAX> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V<const MIN: usize, const MAX: usize>;
        impl<'de, const MIN: usize, const MAX: usize> Visitor<'de> for V<MIN, MAX> {
            type Value = Points<MIN, MAX>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("an array of [x, y] points")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Self::Value, A::Error> {
                let xy: Vec<Xy> = bounded_seq(seq, (MIN, MAX), |n| count_message(MIN, MAX, n))?;
                Ok(Points(xy.into_iter().map(|p| p.0).collect()))
            }
        }
        d.deserialize_seq(V::<MIN, MAX>)
    }
}

impl<const MIN: usize, const MAX: usize> JsonSchema for Points<MIN, MAX> {
    fn inline_schema() -> bool {
        true
    }
    fn schema_name() -> Cow<'static, str> {
        format!("Points{MIN}to{MAX}").into()
    }
    fn json_schema(g: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "type": "array", "items": g.subschema_for::<Xy>(),
            "minItems": MIN, "maxItems": MAX
        })
    }
}

/// An integer from `LO` to `HI`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntIn<const LO: u64, const HI: u64>(pub u64);

impl<'de, const LO: u64, const HI: u64> Deserialize<'de> for IntIn<LO, HI> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V<const LO: u64, const HI: u64>;
        impl<'de, const LO: u64, const HI: u64> Visitor<'de> for V<LO, HI> {
            type Value = IntIn<LO, HI>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(f, "an integer from {LO} to {HI}")
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
                if (LO..=HI).contains(&v) {
                    Ok(IntIn(v))
                } else {
                    Err(E::invalid_value(de::Unexpected::Unsigned(v), &self))
                }
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
                match u64::try_from(v) {
                    Ok(u) => self.visit_u64(u),
                    Err(_) => Err(E::invalid_value(de::Unexpected::Signed(v), &self)),
                }
            }
        }
        d.deserialize_u64(V::<LO, HI>)
    }
}

impl<const LO: u64, const HI: u64> JsonSchema for IntIn<LO, HI> {
    fn inline_schema() -> bool {
        true
    }
    fn schema_name() -> Cow<'static, str> {
        format!("Int{LO}to{HI}").into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({"type": "integer", "minimum": LO, "maximum": HI})
    }
}

/// A positive number (a tolerance, a distance); the wording is the library's
/// ([`aesthetic_curves::Error::check_positive`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Positive(pub f64);

impl<'de> Deserialize<'de> for Positive {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = f64::deserialize(d)?;
        aesthetic_curves::Error::check_positive("", v)
            .map_err(|_| de::Error::custom("must be a positive number"))?;
        Ok(Positive(v))
    }
}

impl JsonSchema for Positive {
    fn inline_schema() -> bool {
        true
    }
    fn schema_name() -> Cow<'static, str> {
        "Positive".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({"type": "number", "exclusiveMinimum": 0})
    }
}

/// A number of at least zero (a grid step: 0 for none).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NonNegative(pub f64);

impl<'de> Deserialize<'de> for NonNegative {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = f64::deserialize(d)?;
        if v >= 0.0 {
            Ok(NonNegative(v))
        } else {
            Err(de::Error::custom("must be a number >= 0"))
        }
    }
}

impl JsonSchema for NonNegative {
    fn inline_schema() -> bool {
        true
    }
    fn schema_name() -> Cow<'static, str> {
        "NonNegative".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({"type": "number", "minimum": 0})
    }
}

/// Points per piece of a `drawing` (the `draw` field).
pub type Draw = IntIn<2, { super::drawing::MAX_DRAW_SAMPLES }>;

/// Weights of control points: positive, one per point (the count is the request's check).
pub type Weights = Vec<Positive>;

/// The numbers of [`Weights`].
pub fn weights(w: &[Positive]) -> Vec<f64> {
    w.iter().map(|p| p.0).collect()
}

/// A list of `MIN` to `MAX` items (the count is checked before the items are read).
#[derive(Debug, Clone, PartialEq)]
pub struct List<T, const MIN: usize, const MAX: usize>(pub Vec<T>);

impl<'de, T: Deserialize<'de>, const MIN: usize, const MAX: usize> Deserialize<'de>
    for List<T, MIN, MAX>
{
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V<T, const MIN: usize, const MAX: usize>(std::marker::PhantomData<T>);
        impl<'de, T: Deserialize<'de>, const MIN: usize, const MAX: usize> Visitor<'de> for V<T, MIN, MAX> {
            type Value = List<T, MIN, MAX>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(f, "an array of {MIN} to {MAX} items")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Self::Value, A::Error> {
                let message = |n: usize| format!("must hold {MIN} to {MAX} items, got {n}");
                Ok(List(bounded_seq(seq, (MIN, MAX), message)?))
            }
        }
        d.deserialize_seq(V::<T, MIN, MAX>(std::marker::PhantomData))
    }
}

impl<T: JsonSchema, const MIN: usize, const MAX: usize> JsonSchema for List<T, MIN, MAX> {
    fn inline_schema() -> bool {
        true
    }
    fn schema_name() -> Cow<'static, str> {
        format!("List{MIN}to{MAX}_{}", T::schema_name()).into()
    }
    fn json_schema(g: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "type": "array", "items": g.subschema_for::<T>(),
            "minItems": MIN, "maxItems": MAX
        })
    }
}
