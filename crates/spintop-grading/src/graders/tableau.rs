//! Which stage of a student's Runge–Kutta step is wrong.
//!
//! An explicit Runge–Kutta step is its Butcher tableau: the time of each
//! stage (c), the slopes each stage steps from (a row of A), the weights of
//! the step (b) and, for an embedded pair, the weights of the lower-order
//! solution (b̂). A slip in a student's step is almost always one entry of
//! that table, or one row (a line copied from the one above). The student's
//! step is called on a few test fields chosen so that every entry shows
//! (a field of t alone weighs the nodes as a quadrature does, a chain
//! y₂' = y₁, y₃' = y₂ passes each stage on to the next, a linear decay reads
//! the stages' products), and each single entry, then each row, is fitted
//! to the answers by Gauss–Newton. A slip is named only when the fitted
//! table reproduces every answer to rounding, the failing input included,
//! and no other entry does.

use spintop::math::{Real, State};

/// A right-hand side f(t, y).
pub(crate) type Rhs<'a> = &'a dyn Fn(Real, &State<3>) -> State<3>;

/// An explicit Runge–Kutta step: c, A (below the diagonal), b and, for an
/// embedded pair, b̂ over the stages plus one more, the "first same as last"
/// stage f(t + c_last h, y_new).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Tableau {
    pub(crate) c: Vec<Real>,
    pub(crate) a: Vec<Vec<Real>>,
    pub(crate) b: Vec<Real>,
    pub(crate) bhat: Option<Vec<Real>>,
}

/// One entry of a tableau. Stages count from 0 here; the words count from 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Entry {
    /// The time of a stage (for an embedded pair, index s is the last stage).
    C(usize),
    /// The coefficient of stage i on the slope of stage j.
    A(usize, usize),
    /// The weight of a stage in the step.
    B(usize),
    /// The weight of a stage in the embedded solution.
    Bhat(usize),
}

impl Tableau {
    /// The classical RK4 (Hairer–Nørsett–Wanner I, Table II.1.2).
    pub(crate) fn rk4() -> Self {
        Self {
            c: vec![0.0, 0.5, 0.5, 1.0],
            a: vec![vec![], vec![0.5], vec![0.0, 0.5], vec![0.0, 0.0, 1.0]],
            b: [1.0, 2.0, 2.0, 1.0].iter().map(|w| w / 6.0).collect(),
            bhat: None,
        }
    }

    /// Dormand–Prince 5(4) (Hairer–Nørsett–Wanner I, Table II.5.2); its
    /// seventh stage is f(t + h, y₅).
    pub(crate) fn dp5() -> Self {
        Self {
            c: vec![0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0],
            a: vec![
                vec![],
                vec![0.2],
                vec![3.0 / 40.0, 9.0 / 40.0],
                vec![44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
                vec![
                    19372.0 / 6561.0,
                    -25360.0 / 2187.0,
                    64448.0 / 6561.0,
                    -212.0 / 729.0,
                ],
                vec![
                    9017.0 / 3168.0,
                    -355.0 / 33.0,
                    46732.0 / 5247.0,
                    49.0 / 176.0,
                    -5103.0 / 18656.0,
                ],
            ],
            b: vec![
                35.0 / 384.0,
                0.0,
                500.0 / 1113.0,
                125.0 / 192.0,
                -2187.0 / 6784.0,
                11.0 / 84.0,
            ],
            bhat: Some(vec![
                5179.0 / 57600.0,
                0.0,
                7571.0 / 16695.0,
                393.0 / 640.0,
                -92097.0 / 339200.0,
                187.0 / 2100.0,
                1.0 / 40.0,
            ]),
        }
    }

    /// The number of stages of the step (without the embedded pair's last).
    pub(crate) fn stages(&self) -> usize {
        self.b.len()
    }

    /// Every entry a slip can change.
    pub(crate) fn entries(&self) -> Vec<Entry> {
        let s = self.stages();
        let mut out: Vec<Entry> = (1..self.c.len()).map(Entry::C).collect();
        out.extend((1..s).flat_map(|i| (0..i).map(move |j| Entry::A(i, j))));
        out.extend((0..s).map(Entry::B));
        if let Some(bhat) = &self.bhat {
            out.extend((0..bhat.len()).map(Entry::Bhat));
        }
        out
    }

    /// The entries of stage i's row: its time and its coefficients.
    pub(crate) fn row(&self, i: usize) -> Vec<Entry> {
        std::iter::once(Entry::C(i))
            .chain((0..i).map(|j| Entry::A(i, j)))
            .collect()
    }

    pub(crate) fn get(&self, e: Entry) -> Real {
        match e {
            Entry::C(i) => self.c[i],
            Entry::A(i, j) => self.a[i][j],
            Entry::B(i) => self.b[i],
            Entry::Bhat(i) => self.bhat.as_ref().map_or(Real::NAN, |b| b[i]),
        }
    }

    pub(crate) fn set(&mut self, e: Entry, v: Real) {
        match e {
            Entry::C(i) => self.c[i] = v,
            Entry::A(i, j) => self.a[i][j] = v,
            Entry::B(i) => self.b[i] = v,
            Entry::Bhat(i) => {
                if let Some(b) = self.bhat.as_mut() {
                    b[i] = v;
                }
            }
        }
    }

    /// One step: the new state's numbers, then (for an embedded pair) the
    /// error estimate's, the higher-order solution minus the lower-order one.
    pub(crate) fn step(&self, f: Rhs<'_>, t: Real, y: &State<3>, h: Real) -> Vec<Real> {
        let s = self.stages();
        let mut k: Vec<State<3>> = Vec::with_capacity(s + 1);
        for i in 0..s {
            let mut yi = *y;
            for (j, kj) in k.iter().enumerate() {
                yi += kj * (self.a[i][j] * h);
            }
            k.push(f(t + self.c[i] * h, &yi));
        }
        let mut next = *y;
        for (kj, bj) in k.iter().zip(&self.b) {
            next += kj * (bj * h);
        }
        let mut out = next.as_slice().to_vec();
        if let Some(bhat) = &self.bhat {
            k.push(f(t + self.c[s] * h, &next));
            let mut low = *y;
            for (kj, bj) in k.iter().zip(bhat) {
                low += kj * (bj * h);
            }
            out.extend((next - low).iter());
        }
        out
    }
}

/// A student's answers to a set of probes: each probe's field, time, state
/// and step, and the numbers the student returned.
pub(crate) struct Observed<'a> {
    pub(crate) probes: Vec<(Rhs<'a>, Real, State<3>, Real)>,
    pub(crate) theirs: Vec<Vec<Real>>,
}

impl Observed<'_> {
    /// The misfit of `table` to the answers, each probe's numbers scaled by
    /// their size.
    fn residual(&self, table: &Tableau) -> Vec<Real> {
        let mut out = Vec::new();
        for ((f, t, y, h), theirs) in self.probes.iter().zip(&self.theirs) {
            let scale = 1.0 + theirs.iter().map(|v| v * v).sum::<Real>().sqrt();
            let mine = table.step(*f, *t, y, *h);
            out.extend(mine.iter().zip(theirs).map(|(m, o)| (m - o) / scale));
        }
        out
    }

    /// Whether `table` reproduces every answer to rounding.
    pub(crate) fn fits(&self, table: &Tableau) -> bool {
        norm(&self.residual(table)) <= 1e-11 * (self.probes.len() as Real).sqrt()
    }

    /// The values of `free` that make `start` fit best (Gauss–Newton with
    /// Levenberg's damping), from the entries' values in `start`.
    fn fit(&self, start: &Tableau, free: &[Entry]) -> Tableau {
        let n = free.len();
        let mut table = start.clone();
        let mut r = self.residual(&table);
        let mut damping = 1e-6;
        for _ in 0..60 {
            if norm(&r) <= 1e-14 {
                break;
            }
            // The Jacobian by differences (the step is a polynomial in each
            // entry, so its differences are smooth).
            let mut jac = Vec::with_capacity(n);
            for &e in free {
                let v = table.get(e);
                let dv = 1e-7 * v.abs().max(1.0);
                let mut moved = table.clone();
                moved.set(e, v + dv);
                let rm = self.residual(&moved);
                jac.push(
                    rm.iter()
                        .zip(&r)
                        .map(|(a, b)| (a - b) / dv)
                        .collect::<Vec<_>>(),
                );
            }
            let mut improved = false;
            for _ in 0..8 {
                let Some(delta) = damped_step(&jac, &r, damping) else {
                    return table;
                };
                let mut next = table.clone();
                for (&e, d) in free.iter().zip(&delta) {
                    next.set(e, next.get(e) + d);
                }
                let rn = self.residual(&next);
                if norm(&rn) < norm(&r) {
                    table = next;
                    r = rn;
                    damping = (damping / 10.0).max(1e-12);
                    improved = true;
                    break;
                }
                damping *= 10.0;
            }
            if !improved {
                break;
            }
        }
        table
    }
}

fn norm(v: &[Real]) -> Real {
    v.iter().map(|x| x * x).sum::<Real>().sqrt()
}

/// Solve (JᵀJ + μ diag(JᵀJ)) δ = −Jᵀr for the few unknowns of a fit.
fn damped_step(jac: &[Vec<Real>], r: &[Real], damping: Real) -> Option<Vec<Real>> {
    let n = jac.len();
    let mut m = nalgebra::DMatrix::<Real>::zeros(n, n);
    let mut g = nalgebra::DVector::<Real>::zeros(n);
    for p in 0..n {
        g[p] = -jac[p].iter().zip(r).map(|(a, b)| a * b).sum::<Real>();
        for q in 0..n {
            m[(p, q)] = jac[p].iter().zip(&jac[q]).map(|(a, b)| a * b).sum::<Real>();
        }
    }
    for p in 0..n {
        m[(p, p)] += damping * m[(p, p)].max(1e-300);
    }
    let delta = m.lu().solve(&g)?;
    delta
        .iter()
        .all(|d| d.is_finite())
        .then(|| delta.iter().copied().collect())
}

/// A slip found: the entries that differ from the method's table, with the
/// student's values.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Slip {
    pub(crate) changed: Vec<(Entry, Real)>,
}

/// The entries of `free` that `fitted` changed (beyond rounding) from `right`.
fn changed(right: &Tableau, fitted: &Tableau, free: &[Entry]) -> Vec<(Entry, Real)> {
    free.iter()
        .filter(|&&e| (fitted.get(e) - right.get(e)).abs() > 1e-8 * (1.0 + right.get(e).abs()))
        .map(|&e| (e, snap(fitted.get(e))))
        .collect()
}

/// The first continued-fraction convergent p/q (q ≤ 10⁶) of |v| within
/// `tol` of it.
fn convergent(v: Real, tol: Real) -> Option<(Real, Real)> {
    let (mut h0, mut h1, mut k0, mut k1) = (0.0, 1.0, 1.0, 0.0);
    let mut x = v.abs();
    for _ in 0..20 {
        let a = x.floor();
        (h0, h1) = (h1, a * h1 + h0);
        (k0, k1) = (k1, a * k1 + k0);
        if k1 > 1e6 {
            return None;
        }
        if (h1 / k1 - v.abs()).abs() <= tol * v.abs().max(1.0) {
            return Some((h1, k1));
        }
        let frac = x - a;
        if frac < 1e-15 {
            return None;
        }
        x = 1.0 / frac;
    }
    None
}

/// A fitted value as the fraction it is within the fit's accuracy (a slip
/// writes 0, −56/15 or 8/9, and the fit finds it to about 1e-12).
fn snap(v: Real) -> Real {
    if v.abs() < 1e-10 {
        return 0.0;
    }
    convergent(v, 1e-10).map_or(v, |(p, q)| v.signum() * p / q)
}

/// The single entry, or else the single row, or else the embedded weights,
/// that explain the student's answers; `None` if none does, or if more than
/// one single entry does (the probes cannot tell them apart).
pub(crate) fn find_slip(right: &Tableau, seen: &Observed<'_>) -> Option<Slip> {
    let mut singles = Vec::new();
    for e in right.entries() {
        let v = right.get(e);
        for start in [v, 0.0, -v, 2.0 * v + 0.1, 0.5 * v - 0.1] {
            let mut from = right.clone();
            from.set(e, start);
            let fitted = seen.fit(&from, &[e]);
            if seen.fits(&fitted) {
                let c = changed(right, &fitted, &[e]);
                if !c.is_empty() {
                    singles.push(Slip { changed: c });
                }
                break;
            }
        }
    }
    match singles.len() {
        1 => return singles.pop(),
        0 => {}
        _ => return None,
    }
    let mut groups: Vec<Vec<Entry>> = (1..right.stages()).map(|i| right.row(i)).collect();
    groups.push((0..right.stages()).map(Entry::B).collect());
    if let Some(bhat) = &right.bhat {
        groups.push((0..bhat.len()).map(Entry::Bhat).collect());
    }
    for free in groups {
        let fitted = seen.fit(right, &free);
        if seen.fits(&fitted) {
            let c = changed(right, &fitted, &free);
            if !c.is_empty() {
                return Some(Slip { changed: c });
            }
        }
    }
    None
}

/// `v` as a fraction when it is one with a small denominator ("8/9",
/// "−56/15"), else in decimals.
pub(crate) fn fraction(v: Real) -> String {
    let text = match convergent(v, 1e-12) {
        Some((0.0, _)) => "0".to_string(),
        Some((p, 1.0)) => format!("{}", v.signum() * p),
        Some((p, q)) => format!("{}{p}/{q}", if v < 0.0 { "-" } else { "" }),
        None => format!("{v:.6}"),
    };
    text.replace('-', "−")
}

const ORDINALS: [&str; 7] = [
    "first", "second", "third", "fourth", "fifth", "sixth", "seventh",
];

/// "stage 3 (k3)".
fn stage(i: usize) -> String {
    format!("stage {} (k{})", i + 1, i + 1)
}

/// How a student's value relates to the table's, in words.
fn relation(theirs: Real, right: Real) -> String {
    if right != 0.0 && (theirs + right).abs() <= 1e-9 * right.abs() {
        "has the wrong sign".into()
    } else if theirs.abs() <= 1e-12 {
        "is missing (zero)".into()
    } else if right == 0.0 {
        format!("is {}, where the table has none", fraction(theirs))
    } else {
        let k = theirs / right;
        let simple = [2.0, 0.5, 3.0, 1.0 / 3.0, 4.0, 0.25];
        match simple.iter().find(|s| (k / *s - 1.0).abs() < 1e-9) {
            Some(s) => format!("is {} times the table's", fraction(*s)),
            None => format!("is {}, not the table's", fraction(theirs)),
        }
    }
}

/// Where in the step a stage's time lies, for the words.
fn time_words(table: &Tableau, i: usize, v: Real) -> String {
    let same: Vec<usize> = (0..table.c.len())
        .filter(|&j| j != i && (table.c[j] - v).abs() < 1e-12)
        .collect();
    let at = match v {
        0.0 => "at the start of the step, t".to_string(),
        1.0 => "at the end of the step, t + h".to_string(),
        0.5 => "at the midpoint, t + h/2".to_string(),
        _ => format!("at t + {} h", fraction(v)),
    };
    match same.first() {
        Some(&j) if j != 0 && v != 0.0 && v != 1.0 => {
            format!("{at}, the time of stage {} (a line copied?)", j + 1)
        }
        _ => at,
    }
}

/// The words of a slip (which stage, which entry, how), never the table.
pub(crate) fn slip_words(right: &Tableau, slip: &Slip) -> String {
    let check = "check it against the method's table";
    match slip.changed.as_slice() {
        [(Entry::C(i), v)] => format!(
            "{} is evaluated at the wrong time: yours {}; {check}",
            stage(*i),
            time_words(right, *i, *v)
        ),
        [(Entry::A(i, j), v)] => {
            let only = right.a[*i].iter().filter(|x| **x != 0.0).count() == 1;
            let r = right.a[*i][*j];
            if only && r != 0.0 && *v > 0.0 {
                let how_far = |x: Real| match x {
                    0.5 => "half a step".to_string(),
                    1.0 => "a full step".to_string(),
                    _ => format!("{} of a step", fraction(x)),
                };
                format!(
                    "{} steps the wrong distance: yours goes {} along k{}, where the {} stage goes {}",
                    stage(*i),
                    how_far(*v),
                    j + 1,
                    ORDINALS[*i],
                    how_far(r)
                )
            } else {
                format!(
                    "{} steps from the wrong state: its coefficient on k{} {}; {check}",
                    stage(*i),
                    j + 1,
                    relation(*v, r)
                )
            }
        }
        [(Entry::B(i), v)] => format!(
            "the weight of {} in the step {}; {check}",
            stage(*i),
            relation(*v, right.b[*i])
        ),
        [(Entry::Bhat(i), v)] => {
            let r = right.bhat.as_ref().map_or(0.0, |b| b[*i]);
            let last = right.bhat.as_ref().is_some_and(|b| *i == b.len() - 1);
            let extra = if last {
                " (the seventh stage is f at the end of the step, from the new state)"
            } else {
                ""
            };
            format!(
                "the step is right, the error estimate is not: the embedded (lower-order) weight of {} {}{extra}; {check}",
                stage(*i),
                relation(*v, r)
            )
        }
        changed => group_words(right, changed),
    }
}

/// The words of several entries of one row, of the weights, or of the
/// embedded weights.
fn group_words(right: &Tableau, changed: &[(Entry, Real)]) -> String {
    let row = |e: &Entry| match e {
        Entry::C(i) | Entry::A(i, _) => Some(*i),
        _ => None,
    };
    if let Some(i) = changed.first().and_then(|(e, _)| row(e)) {
        let coefficients: Vec<(usize, Real)> = changed
            .iter()
            .filter_map(|(e, v)| match e {
                Entry::A(_, j) => Some((*j, *v)),
                _ => None,
            })
            .collect();
        if let [(j, vj), (l, vl)] = coefficients.as_slice() {
            let (rj, rl) = (right.a[i][*j], right.a[i][*l]);
            let near = |a: Real, b: Real| (a - b).abs() <= 1e-9 * (1.0 + b.abs());
            if near(*vj, rl) && near(*vl, rj) && rl != 0.0 && rj != 0.0 {
                return format!(
                    "{} steps from the wrong state: its coefficients on k{} and k{} are swapped",
                    stage(i),
                    j + 1,
                    l + 1
                );
            }
            if near(*vj, rl) && *vl == 0.0 && rj == 0.0 {
                return format!(
                    "{} steps from the wrong slope: from k{}, where the table has k{}",
                    stage(i),
                    j + 1,
                    l + 1
                );
            }
            if near(*vl, rj) && *vj == 0.0 && rl == 0.0 {
                return format!(
                    "{} steps from the wrong slope: from k{}, where the table has k{}",
                    stage(i),
                    l + 1,
                    j + 1
                );
            }
        }
        let parts: Vec<String> = changed
            .iter()
            .map(|(e, v)| match e {
                Entry::C(_) => format!("its time is {}", time_words(right, i, *v)),
                Entry::A(_, j) => format!(
                    "its coefficient on k{} {}",
                    j + 1,
                    relation(*v, right.a[i][*j])
                ),
                _ => String::new(),
            })
            .collect();
        return format!(
            "{} is wrong: {}; check its row against the method's table",
            stage(i),
            parts.join(", and ")
        );
    }
    let embedded = matches!(changed.first(), Some((Entry::Bhat(_), _)));
    let names: Vec<String> = changed
        .iter()
        .map(|(e, _)| match e {
            Entry::B(i) | Entry::Bhat(i) => format!("k{}", i + 1),
            _ => String::new(),
        })
        .collect();
    if embedded {
        format!(
            "the step is right, the error estimate is not: the embedded (lower-order) weights of {} are wrong (the seventh stage is f at the end of the step, from the new state); check them against the method's table",
            names.join(", ")
        )
    } else {
        format!(
            "the stages are right, the weights of {} in the step are not; check them against the method's table",
            names.join(", ")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use spintop::integrate::{dopri5::dopri5_step, rk4::rk4_step};

    fn field(t: Real, y: &State<3>) -> State<3> {
        State::<3>::new(
            -0.5 * y[0] + 2.0 * y[1] + t.sin(),
            y[0] * y[2],
            -y[2] + t * t,
        )
    }

    #[test]
    fn the_tables_are_the_methods() {
        let y = State::<3>::new(0.3, -0.7, 1.1);
        let rk4 = Tableau::rk4().step(&field, 0.4, &y, 0.3);
        let want = rk4_step(&field, 0.4, &y, 0.3);
        assert!((State::<3>::from_row_slice(&rk4) - want).norm() < 1e-15);
        let dp5 = Tableau::dp5().step(&field, 0.4, &y, 0.3);
        let (y5, e) = dopri5_step(&field, 0.4, &y, 0.3);
        assert!((State::<3>::from_row_slice(&dp5[..3]) - y5).norm() < 1e-15);
        assert!((State::<3>::from_row_slice(&dp5[3..]) - e).norm() < 1e-15);
    }

    #[test]
    fn fractions_are_read_back() {
        assert_eq!(fraction(8.0 / 9.0), "8/9");
        assert_eq!(fraction(-56.0 / 15.0), "−56/15");
        assert_eq!(fraction(-2187.0 / 6784.0), "−2187/6784");
        assert_eq!(fraction(2.0), "2");
        assert_eq!(fraction(0.5), "1/2");
    }
}
