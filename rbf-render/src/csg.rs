//! Constructive solid geometry on implicit functions that are positive inside: union is the
//! maximum, intersection the minimum, and A minus B is min(f_A, −f_B)
//! (Turk & O'Brien 2002, Figure 10).

use crate::RenderError;

/// A solid built from the models of a scene (by index).
///
/// ```
/// use rbf_render::Csg;
/// let shape = Csg::Difference(Box::new(Csg::Model(0)), Box::new(Csg::Model(1)));
/// assert_eq!(shape.models(), vec![0, 1]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum Csg {
    /// One model, by 0-based index into the views passed to the render: inside where f > 0.
    Model(usize),
    /// Inside any part.
    Union(Vec<Csg>),
    /// Inside every part.
    Intersection(Vec<Csg>),
    /// Inside the first and outside the second.
    Difference(Box<Csg>, Box<Csg>),
}

impl Csg {
    /// The models used, in order of first use, each once.
    pub fn models(&self) -> Vec<usize> {
        let mut out = Vec::new();
        self.collect(&mut out);
        out
    }

    fn collect(&self, out: &mut Vec<usize>) {
        match self {
            Csg::Model(i) => {
                if !out.contains(i) {
                    out.push(*i);
                }
            }
            Csg::Union(parts) | Csg::Intersection(parts) => {
                parts.iter().for_each(|p| p.collect(out));
            }
            Csg::Difference(a, b) => {
                a.collect(out);
                b.collect(out);
            }
        }
    }

    /// Checks that every model index is below `models` and no union or intersection is empty.
    pub(crate) fn validate(&self, models: usize) -> Result<(), RenderError> {
        match self {
            Csg::Model(i) if *i >= models => Err(RenderError::NoSuchModel { index: *i, models }),
            Csg::Model(_) => Ok(()),
            Csg::Union(parts) | Csg::Intersection(parts) => {
                if parts.is_empty() {
                    return Err(RenderError::EmptyCsg);
                }
                parts.iter().try_for_each(|p| p.validate(models))
            }
            Csg::Difference(a, b) => {
                a.validate(models)?;
                b.validate(models)
            }
        }
    }

    /// The solid's function, the model whose value it is, and the sign with which it enters
    /// (−1 for a subtracted model): its surface is that model's, its outward normal that
    /// model's −sign·∇f.
    pub(crate) fn active(&self, values: &[f64]) -> (f64, usize, f64) {
        match self {
            Csg::Model(i) => (values[*i], *i, 1.0),
            Csg::Union(parts) => pick(parts, values, |a, b| a > b),
            Csg::Intersection(parts) => pick(parts, values, |a, b| a < b),
            Csg::Difference(a, b) => {
                let x = a.active(values);
                let (v, i, s) = b.active(values);
                if -v < x.0 { (-v, i, -s) } else { x }
            }
        }
    }

    /// Bounds on the solid's function from bounds (lo, hi) on every model's.
    pub(crate) fn interval(&self, bounds: &[(f64, f64)]) -> (f64, f64) {
        match self {
            Csg::Model(i) => bounds[*i],
            Csg::Union(parts) => parts
                .iter()
                .map(|p| p.interval(bounds))
                .fold((f64::NEG_INFINITY, f64::NEG_INFINITY), |a, b| {
                    (a.0.max(b.0), a.1.max(b.1))
                }),
            Csg::Intersection(parts) => parts
                .iter()
                .map(|p| p.interval(bounds))
                .fold((f64::INFINITY, f64::INFINITY), |a, b| {
                    (a.0.min(b.0), a.1.min(b.1))
                }),
            Csg::Difference(a, b) => {
                let (alo, ahi) = a.interval(bounds);
                let (blo, bhi) = b.interval(bounds);
                (alo.min(-bhi), ahi.min(-blo))
            }
        }
    }
}

fn pick(parts: &[Csg], values: &[f64], better: impl Fn(f64, f64) -> bool) -> (f64, usize, f64) {
    let mut best = (f64::NAN, 0, 1.0);
    for p in parts {
        let x = p.active(values);
        if best.0.is_nan() || better(x.0, best.0) {
            best = x;
        }
    }
    best
}
