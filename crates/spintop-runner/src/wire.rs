//! The wire: an assignment's arguments and its answer as a list of numbers,
//! one line of text each way.
//!
//! Every number is printed with Rust's shortest round-trip form (`{:?}`),
//! which parses back to the same bits (`NaN` and the infinities included),
//! so an answer crosses the pipe exactly: the graders compare it to 1e-13.

use crate::fields::Field;
use spintop::assignment::{C, Mat3, Real, State};

/// The most numbers one line may carry (the largest call takes 21 for a
/// field and 5 more; the largest answer, 12).
pub const MAX_NUMBERS: usize = 64;

/// A value that travels as numbers.
pub trait Wire: Sized {
    /// Appends its numbers to `out`.
    fn put(&self, out: &mut Vec<Real>);
    /// Takes its numbers from the front of `from`; `None` if they are not
    /// there or do not make one.
    fn take(from: &mut &[Real]) -> Option<Self>;
}

/// The numbers of `value`.
pub fn numbers<T: Wire>(value: &T) -> Vec<Real> {
    let mut out = Vec::new();
    value.put(&mut out);
    out
}

/// The value made of exactly `numbers` (none left over).
pub fn value<T: Wire>(numbers: &[Real]) -> Option<T> {
    let mut rest = numbers;
    let v = T::take(&mut rest)?;
    rest.is_empty().then_some(v)
}

/// Numbers as text: separated by spaces, each in its shortest exact form.
pub fn text(numbers: &[Real]) -> String {
    let words: Vec<String> = numbers.iter().map(|x| format!("{x:?}")).collect();
    words.join(" ")
}

/// The numbers of a text made by [`text`] (at most [`MAX_NUMBERS`]).
pub fn parse(text: &str) -> Option<Vec<Real>> {
    let mut out = Vec::new();
    for word in text.split_ascii_whitespace() {
        if out.len() == MAX_NUMBERS {
            return None;
        }
        out.push(word.parse::<Real>().ok()?);
    }
    Some(out)
}

fn one(from: &mut &[Real]) -> Option<Real> {
    let (first, rest) = from.split_first()?;
    *from = rest;
    Some(*first)
}

impl Wire for Real {
    fn put(&self, out: &mut Vec<Real>) {
        out.push(*self);
    }
    fn take(from: &mut &[Real]) -> Option<Self> {
        one(from)
    }
}

/// A count (a number of steps): a whole number, exactly, below 2⁵³.
impl Wire for usize {
    fn put(&self, out: &mut Vec<Real>) {
        out.push(*self as Real);
    }
    fn take(from: &mut &[Real]) -> Option<Self> {
        let x = one(from)?;
        (x >= 0.0 && x.fract() == 0.0 && x < 9_007_199_254_740_992.0).then_some(x as usize)
    }
}

impl<const N: usize> Wire for State<N> {
    fn put(&self, out: &mut Vec<Real>) {
        out.extend(self.iter());
    }
    fn take(from: &mut &[Real]) -> Option<Self> {
        if from.len() < N {
            return None;
        }
        let (mine, rest) = from.split_at(N);
        *from = rest;
        Some(State::<N>::from_column_slice(mine))
    }
}

/// A matrix, column by column.
impl Wire for Mat3 {
    fn put(&self, out: &mut Vec<Real>) {
        out.extend(self.iter());
    }
    fn take(from: &mut &[Real]) -> Option<Self> {
        if from.len() < 9 {
            return None;
        }
        let (mine, rest) = from.split_at(9);
        *from = rest;
        Some(Mat3::from_column_slice(mine))
    }
}

impl Wire for C {
    fn put(&self, out: &mut Vec<Real>) {
        out.extend([self.re, self.im]);
    }
    fn take(from: &mut &[Real]) -> Option<Self> {
        Some(C::new(one(from)?, one(from)?))
    }
}

impl<T: Wire, const K: usize> Wire for [T; K] {
    fn put(&self, out: &mut Vec<Real>) {
        for v in self {
            v.put(out);
        }
    }
    fn take(from: &mut &[Real]) -> Option<Self> {
        let items: Vec<T> = (0..K).map(|_| T::take(from)).collect::<Option<_>>()?;
        items.try_into().ok()
    }
}

impl Wire for Field {
    fn put(&self, out: &mut Vec<Real>) {
        out.extend(self.numbers());
    }
    fn take(from: &mut &[Real]) -> Option<Self> {
        Field::from_numbers(from)
    }
}

macro_rules! tuple_wire {
    ($($t:ident),+) => {
        impl<$($t: Wire),+> Wire for ($($t,)+) {
            #[allow(non_snake_case)]
            fn put(&self, out: &mut Vec<Real>) {
                let ($($t,)+) = self;
                $($t.put(out);)+
            }
            fn take(from: &mut &[Real]) -> Option<Self> {
                Some(($($t::take(from)?,)+))
            }
        }
    };
}

tuple_wire!(A);
tuple_wire!(A, B);
tuple_wire!(A, B, D);
tuple_wire!(A, B, D, E);
tuple_wire!(A, B, D, E, F);

#[cfg(test)]
mod tests {
    use super::*;
    use spintop::assignment::Vec3;

    #[test]
    fn every_number_crosses_the_wire_to_the_same_bits() {
        let xs = [
            0.1,
            -0.0,
            1e-300,
            5e-324,
            Real::MAX,
            Real::NAN,
            Real::INFINITY,
            Real::NEG_INFINITY,
            std::f64::consts::PI,
        ];
        let back = parse(&text(&xs)).unwrap();
        for (a, b) in xs.iter().zip(&back) {
            assert_eq!(a.to_bits(), b.to_bits(), "{a:?} came back as {b:?}");
        }
    }

    #[test]
    fn a_value_is_made_of_exactly_its_numbers() {
        let jet = [
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::new(4.0, 5.0, 6.0),
            Vec3::new(7.0, 8.0, 9.0),
            Vec3::new(10.0, 11.0, 12.0),
        ];
        let n = numbers(&(jet,));
        assert_eq!(n.len(), 12);
        assert_eq!(value::<([Vec3; 4],)>(&n), Some((jet,)));
        // One number short, one too many: no value.
        assert_eq!(value::<([Vec3; 4],)>(&n[..11]), None);
        let mut more = n.clone();
        more.push(0.0);
        assert_eq!(value::<([Vec3; 4],)>(&more), None);
        // A count is a whole number.
        assert_eq!(value::<usize>(&[3.0]), Some(3));
        assert_eq!(value::<usize>(&[3.5]), None);
        assert_eq!(value::<usize>(&[-1.0]), None);
        let m = Mat3::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0);
        assert_eq!(value::<Mat3>(&numbers(&m)), Some(m));
        let c = C::new(0.5, -2.0);
        assert_eq!(value::<(Real, C)>(&numbers(&(1.0, c))), Some((1.0, c)));
    }

    #[test]
    fn garbage_is_no_numbers() {
        assert_eq!(parse("1 2 x"), None);
        assert_eq!(parse(&"1 ".repeat(MAX_NUMBERS + 1)), None);
        assert_eq!(parse(""), Some(vec![]));
    }
}
