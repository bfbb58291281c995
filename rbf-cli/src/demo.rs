//! `rbf demo`: the main job on built-in data — a mesh shipped inside the binary converted to an
//! implicit surface, polygonized and rendered next to the original — then the paper's first
//! examples, fitted and measured. No input, no network.

use std::path::Path;
use std::time::Instant;

use rbf_core::{Constraint, FitSettings, Model, shapes};
use rbf_mesh::{
    PolygonizeSettings, Resolution, polygonize_continuation, surface_seeds, write_mesh,
};

use crate::common::{SPOT, write_atomically};
use crate::failure::{BAD_INPUT, Failure};

/// Radii at which the surface of f crosses rays from the origin in `directions`: where rays
/// cast inward from radius 5 first meet it, by the renderer's sphere tracer.
fn crossings(
    f: &rbf_core::Interpolant<f64, 3>,
    directions: &[[f64; 3]],
) -> Result<Vec<f64>, Failure> {
    const FAR: f64 = 5.0;
    let rays: Vec<rbf_render::Ray> = directions
        .iter()
        .map(|d| rbf_render::Ray {
            origin: d.map(|c| FAR * c),
            direction: d.map(|c| -c),
        })
        .collect();
    let hits = rbf_render::first_hits(
        &[f.view()],
        &rbf_render::Csg::Model(0),
        &rays,
        &rbf_render::RenderSettings::default(),
    )
    .map_err(|e| Failure::new(BAD_INPUT, e.to_string()))?;
    Ok(hits.into_iter().map(|t| FAR - t.unwrap_or(FAR)).collect())
}

/// Converts the built-in mesh, polygonizes the result and renders both side by side.
fn convert_builtin(dir: &Path, say: &dyn Fn(String)) -> Result<(), Failure> {
    let start = Instant::now();
    let mesh = rbf_mesh::read_mesh_bytes(Path::new("spot.obj"), SPOT)
        .map_err(|e| Failure::new(BAD_INPUT, e.to_string()))?;
    let settings = rbf_convert::IterativeSettings {
        resolution: 96,
        ..Default::default()
    };
    let (model, report) = rbf_convert::convert_iterative(&mesh, &settings, |_, _| {})
        .map_err(|e| Failure::new(BAD_INPUT, format!("spot: {e}")))?;
    let best = report.iterations[report.best - 1];
    let converted = start.elapsed().as_secs_f64();
    let model_path = dir.join("spot.json");
    write_atomically(&model_path, model.to_json().as_bytes())?;
    let (surface, _) = polygonize_continuation(
        &model.interpolant.view(),
        &surface_seeds(&model),
        &PolygonizeSettings {
            resolution: Resolution::Cells(128),
            ..Default::default()
        },
    )
    .map_err(|e| Failure::new(BAD_INPUT, format!("spot: {e}")))?;
    let mesh_path = dir.join("spot-implicit.obj");
    write_mesh(&mesh_path, &surface).map_err(|e| Failure::new(BAD_INPUT, e.to_string()))?;
    // The original and the implicit surface from the same camera.
    let (lo, hi) = mesh.bounding_box();
    let camera = rbf_render::Camera::orbit(lo, hi, 215.0, 20.0, 360, 360);
    let png = crate::render::mesh_and_model(&mesh, &model, &camera, rbf_render::MeshStyle::Smooth)?
        .to_png()
        .map_err(|e| Failure::new(BAD_INPUT, e.to_string()))?;
    let png_path = dir.join("spot.png");
    write_atomically(&png_path, &png)?;
    let distance = rbf_convert::surface_distance(
        &model.interpolant.view(),
        &mesh,
        &rbf_convert::CompareSettings {
            samples: 10_000,
            resolution: 128,
            ..Default::default()
        },
    )
    .map_err(|e| Failure::new(BAD_INPUT, format!("spot: {e}")))?;
    let voxel = report.voxel_size;
    let rms = distance
        .mesh_to_surface
        .rms
        .max(distance.surface_to_mesh.rms);
    let count = |k| model.constraints.iter().filter(|c| c.kind == k).count();
    let check = surface.check();
    say(format!(
        "spot the cow ({} triangles, built in) → implicit surface by the iterative method of Yngve & Turk\n  \
         {} voxels, {} iterations, converted in {converted:.1} s: max error {:.2} voxels, RMS {:.2}\n  \
         {} boundary, {} interior, {} exterior constraints\n  \
         distance to the mesh, both ways (rbf compare): RMS {:.2} voxels, Hausdorff {:.2} voxels\n  \
         polygonized: {} triangles, {}\n  \
         wrote {}, {} and {} (the mesh, left, and its implicit surface, right) in {:.1} s",
        mesh.triangles().len(),
        report
            .shape
            .iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(" × "),
        report.iterations.len(),
        best.max_error,
        best.rms_error,
        count(rbf_core::ConstraintKind::Boundary),
        count(rbf_core::ConstraintKind::Interior),
        count(rbf_core::ConstraintKind::Exterior),
        rms / voxel,
        distance.hausdorff() / voxel,
        check.triangles,
        closure(&check),
        model_path.display(),
        mesh_path.display(),
        png_path.display(),
        start.elapsed().as_secs_f64()
    ));
    Ok(())
}

pub(crate) fn run(dir: &Path, quiet: bool) -> Result<(), Failure> {
    std::fs::create_dir_all(dir)
        .map_err(|e| Failure::new(BAD_INPUT, format!("{}: {e}", dir.display())))?;
    let settings = FitSettings::default();
    let say = |s: String| {
        if !quiet {
            println!("{s}");
        }
    };
    let total = Instant::now();
    convert_builtin(dir, &say)?;
    say("\nThe paper's first examples:".into());

    let examples: [(&str, &str, Vec<Constraint<3>>); 3] = [
        (
            "figure2-blob",
            "tetrahedron + centre (Turk & O'Brien 2002, Fig. 2 left)",
            shapes::tetrahedron_blob(),
        ),
        (
            "sculpt-start",
            "tetrahedron in a cube of side 6 (§5)",
            shapes::sculpt_start(),
        ),
        (
            "torus-2000",
            "2000 oriented points on a torus (4000 rows)",
            shapes::torus(2000, 0.35),
        ),
    ];
    for (name, what, constraints) in examples {
        let start = Instant::now();
        let fit = rbf_solve::fit(&constraints, &settings).map_err(|e| Failure::fit(name, &e))?;
        let seconds = start.elapsed().as_secs_f64();
        let f = &fit.interpolant;
        let check = if name.starts_with("torus") {
            // First-order distance |f|/|∇f| at points of the true torus between the constraints.
            let worst = shapes::torus(2001, 0.35)
                .iter()
                .map(|c| {
                    let (v, g) = f.value_and_gradient(&c.position);
                    v.abs() / (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt()
                })
                .fold(0.0_f64, f64::max);
            format!(
                "f(0,0,0) = {:+.3} (the hole is outside); max distance from the true torus at 2001 other points {worst:.1e}",
                f.value(&[0.0; 3])
            )
        } else {
            let radii = crossings(f, &shapes::fibonacci_sphere(200))?;
            let (lo, hi) = radii
                .iter()
                .fold((f64::INFINITY, 0.0_f64), |(a, b), &r| (a.min(r), b.max(r)));
            format!(
                "f(0) = {:+.4} (inside); the surface crosses 200 rays from the centre at radius {lo:.4}…{hi:.4}",
                f.value(&[0.0; 3])
            )
        };
        let path = dir.join(format!("{name}.json"));
        let model = Model {
            constraints,
            settings,
            interpolant: fit.interpolant.clone(),
            report: Some(fit.report),
        };
        write_atomically(&path, model.to_json().as_bytes())?;
        // Its surface as a mesh, by continuation from the constraints.
        let start = Instant::now();
        let settings = PolygonizeSettings {
            resolution: Resolution::Cells(96),
            ..Default::default()
        };
        let (mesh, _) =
            polygonize_continuation(&model.interpolant.view(), &surface_seeds(&model), &settings)
                .map_err(|e| Failure::new(BAD_INPUT, format!("{name}: {e}")))?;
        let mesh_path = dir.join(format!("{name}.obj"));
        write_mesh(&mesh_path, &mesh).map_err(|e| Failure::new(BAD_INPUT, e.to_string()))?;
        let r = mesh.check();
        let meshed = format!(
            "polygonized in {:.3} s: {} triangles, {}; wrote {}",
            start.elapsed().as_secs_f64(),
            r.triangles,
            closure(&r),
            mesh_path.display()
        );
        say(format!(
            "{what}\n  {} rows fitted in {seconds:.3} s ({:?}), residual {:.1e}, condition ≈ {:.1e}\n  {check}\n  wrote {}\n  {meshed}",
            fit.report.rows,
            fit.report.method,
            fit.report.residual,
            fit.report.condition,
            path.display()
        ));
    }
    say(format!(
        "done in {:.1} s. next: rbf render {1}/torus-2000.json -o torus.png --shadows   or   printf '0 0 0\\n2 0 0\\n' | rbf eval {1}/figure2-blob.json -",
        total.elapsed().as_secs_f64(),
        dir.display()
    ));
    Ok(())
}

/// "watertight, genus G" or "open, genus -": how closed a polygonized surface is.
fn closure(r: &rbf_mesh::MeshReport) -> String {
    let genus = r.genus.map_or("-".into(), |g| g.to_string());
    let kind = if r.is_watertight() {
        "watertight"
    } else {
        "open"
    };
    format!("{kind}, genus {genus}")
}
