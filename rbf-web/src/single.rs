//! The studio's field in single precision: the model cast to `f32` (as a device evaluates it)
//! for the polygonizer's values and gradients, which WebAssembly's SIMD runs four lanes wide
//! instead of two. What must be proved (bounds over balls, the surface's box) still reads the
//! `f64` model through [`ScalarField::direct`].
//!
//! The error is far below what a mesh of a few dozen cubes across can show: on a 500-row
//! sphere model, f in `f32` is within 2e-4 of f in `f64`, which places the surface within about
//! 4e-6 of where `f64` does (1e-4 of one of the studio's cubes).

use rbf_core::{Interpolant, InterpolantView, LengthMismatch, ScalarField};

/// A model evaluated in `f32`, its `f64` self kept for [`ScalarField::direct`].
pub(crate) struct SinglePrecision<'a> {
    exact: InterpolantView<'a, f64, 3>,
    single: Interpolant<f32, 3>,
}

impl<'a> SinglePrecision<'a> {
    pub(crate) fn new(model: &'a Interpolant<f64, 3>) -> Self {
        Self {
            exact: model.view(),
            single: model.cast::<f32>(),
        }
    }
}

fn narrowed(points: &[[f64; 3]]) -> Vec<[f32; 3]> {
    points.iter().map(|p| p.map(|c| c as f32)).collect()
}

impl ScalarField<3> for SinglePrecision<'_> {
    fn direct(&self) -> InterpolantView<'_, f64, 3> {
        self.exact
    }

    fn field_values(&self, points: &[[f64; 3]], out: &mut [f64]) -> Result<(), LengthMismatch> {
        let mut values = vec![0.0_f32; out.len()];
        self.single.view().values(&narrowed(points), &mut values)?;
        out.iter_mut().zip(values).for_each(|(o, v)| *o = v as f64);
        Ok(())
    }

    fn field_values_and_gradients(
        &self,
        points: &[[f64; 3]],
        values: &mut [f64],
        gradients: &mut [[f64; 3]],
    ) -> Result<(), LengthMismatch> {
        let mut v = vec![0.0_f32; values.len()];
        let mut g = vec![[0.0_f32; 3]; gradients.len()];
        self.single
            .view()
            .values_and_gradients(&narrowed(points), &mut v, &mut g)?;
        values.iter_mut().zip(v).for_each(|(o, v)| *o = v as f64);
        gradients
            .iter_mut()
            .zip(g)
            .for_each(|(o, g)| *o = g.map(|c| c as f64));
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::SinglePrecision;
    use rbf_core::{Constraint, FitSettings, ScalarField, fit};

    /// The studio's benchmark model (250 oriented points on the unit sphere, 500 rows): the
    /// surface `f32` places is within 1e-5 of the one `f64` places (|Δf| / |∇f|) at points
    /// within a tenth of the sphere, and the gradients agree in direction within 1e-4.
    #[test]
    fn single_precision_moves_the_surface_by_less_than_1e_5() {
        let n = 250;
        let constraints: Vec<Constraint<3>> = (0..n)
            .map(|i| {
                let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
                let (r, a) = ((1.0 - z * z).sqrt(), i as f64 * 2.399963229728653);
                let p = [r * a.cos(), r * a.sin(), z];
                Constraint::normal(p, p)
            })
            .collect();
        let model = fit(&constraints, &FitSettings::default())
            .unwrap()
            .interpolant;
        let points: Vec<[f64; 3]> = (0..2000)
            .map(|i| {
                let (u, v) = (0.37 * i as f64, 1.91 * i as f64);
                let s = 0.9 + 0.2 * (0.013 * i as f64).fract();
                [s * u.cos() * v.sin(), s * u.sin() * v.sin(), s * v.cos()]
            })
            .collect();
        let (mut v64, mut g64) = (vec![0.0; 2000], vec![[0.0; 3]; 2000]);
        model
            .view()
            .field_values_and_gradients(&points, &mut v64, &mut g64)
            .unwrap();
        let single = SinglePrecision::new(&model);
        let (mut v32, mut g32) = (vec![0.0; 2000], vec![[0.0; 3]; 2000]);
        single
            .field_values_and_gradients(&points, &mut v32, &mut g32)
            .unwrap();
        let mut values = vec![0.0; 2000];
        single.field_values(&points, &mut values).unwrap();
        assert_eq!(values, v32);
        let norm = |g: [f64; 3]| (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        for i in 0..2000 {
            let shift = (v32[i] - v64[i]).abs() / norm(g64[i]);
            assert!(shift < 1e-5, "{:?}: {shift}", points[i]);
            let cos =
                (0..3).map(|d| g32[i][d] * g64[i][d]).sum::<f64>() / norm(g32[i]) / norm(g64[i]);
            assert!(cos > 1.0 - 1e-4, "{:?}: {cos}", points[i]);
        }
    }
}
