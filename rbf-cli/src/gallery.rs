//! `rbf gallery`: the figures of Turk & O'Brien (2002) that can be computed, each as a PNG with the
//! models behind it, a `gallery.json` of what each figure measured, and an `index.html`.

use std::f64::consts::FRAC_1_SQRT_2;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use rbf_core::{Constraint, FitSettings, Model, shapes};
use rbf_mesh::{PolygonizeSettings, Resolution, polygonize_grid};
use rbf_render::{Camera, Csg, Image, Object, PlotSettings, RenderSettings, plot_curve, render};
use serde_json::{Value, json};

use crate::common::{SPOT, write_atomically};
use crate::failure::{BAD_INPUT, Failure};
use crate::render::mesh_and_model;

pub(crate) const HELP: &str = "\
Figures 1, 2, 3, 4, 5, 6, 7, 8, 9 and 10 of Turk & O'Brien (2002) and Figure 3 of Yngve & Turk
(2002), recomputed: each a PNG (two
panels side by side where the paper has two), the model files behind it, and what it measured
in gallery.json (watertightness and genus of 3D surfaces, residuals at the constraints of 2D
curves). index.html shows them with one line of caption each.

Example:
  rbf gallery -o gallery && xdg-open gallery/index.html";

#[derive(Args, Debug)]
pub(crate) struct GalleryArgs {
    /// Directory to write.
    #[arg(short, long, default_value = "rbf-gallery")]
    output: PathBuf,
    /// Side of each panel in pixels.
    #[arg(long, default_value_t = 360)]
    size: u32,
}

struct Gallery<'a> {
    dir: &'a Path,
    size: u32,
    entries: Vec<Value>,
}

fn bad(e: impl std::fmt::Display) -> Failure {
    Failure::new(BAD_INPUT, e.to_string())
}

fn fit<const D: usize>(constraints: Vec<Constraint<D>>) -> Result<Model<D>, Failure> {
    let settings = FitSettings::default();
    let fit = rbf_solve::fit(&constraints, &settings).map_err(|e| Failure::fit("gallery", &e))?;
    Ok(Model {
        constraints,
        settings,
        interpolant: fit.interpolant,
        report: Some(fit.report),
    })
}

/// Largest |f| at the model's boundary constraints.
fn boundary_residual<const D: usize>(m: &Model<D>) -> f64 {
    m.constraints
        .iter()
        .filter(|c| c.kind == rbf_core::ConstraintKind::Boundary)
        .map(|c| m.interpolant.value(&c.position).abs())
        .fold(0.0, f64::max)
}

impl Gallery<'_> {
    fn save<const D: usize>(&self, name: &str, m: &Model<D>) -> Result<(), Failure> {
        write_atomically(
            &self.dir.join(format!("{name}.json")),
            m.to_json().as_bytes(),
        )
    }

    fn plot(&self, m: &Model<2>) -> Result<Image, Failure> {
        let settings = PlotSettings {
            width: self.size,
            height: self.size,
            ..Default::default()
        };
        plot_curve(&m.interpolant.view(), &m.constraints, &settings).map_err(bad)
    }

    fn shoot(
        &self,
        models: &[&Model<3>],
        objects: &[Object],
        look: &RenderSettings,
    ) -> Result<Image, Failure> {
        let views: Vec<_> = models.iter().map(|m| m.interpolant.view()).collect();
        let (lo, hi) = rbf_render::surface_bounds(&views, objects, look).map_err(bad)?;
        let camera = Camera::orbit(lo, hi, 30.0, 25.0, self.size, self.size);
        Ok(render(&views, objects, &camera, look).map_err(bad)?.0)
    }

    fn one(&self, m: &Model<3>) -> Result<Image, Failure> {
        let look = RenderSettings {
            shadows: true,
            ..Default::default()
        };
        self.shoot(&[m], &[Object::new(Csg::Model(0), 0)], &look)
    }

    /// Watertightness and genus of a model's surface, polygonized.
    fn topology(&self, m: &Model<3>) -> Result<Value, Failure> {
        let settings = PolygonizeSettings {
            resolution: Resolution::Cells(64),
            ..Default::default()
        };
        let (mesh, _) = polygonize_grid(&m.interpolant.view(), &settings).map_err(bad)?;
        let r = mesh.check();
        Ok(json!({"watertight": r.is_watertight(), "components": r.components, "genus": r.genus}))
    }

    fn add(
        &mut self,
        name: &str,
        caption: &str,
        image: &Image,
        facts: Value,
    ) -> Result<(), Failure> {
        write_atomically(
            &self.dir.join(format!("{name}.png")),
            &image.to_png().map_err(bad)?,
        )?;
        self.entries
            .push(json!({"figure": name, "caption": caption, "facts": facts}));
        Ok(())
    }
}

fn pair(a: &Image, b: &Image) -> Result<Image, Failure> {
    Image::side_by_side(a, b).map_err(bad)
}

/// `n` oriented points on a torus about the y axis at `centre` (radii 1 and 0.35).
fn torus(centre: [f64; 3], n: usize) -> Vec<Constraint<3>> {
    shapes::torus_points(n, 0.35)
        .into_iter()
        .map(|(p, normal)| {
            let [x, y, z] = p;
            let p = [centre[0] + x, centre[1] + z, centre[2] + y];
            Constraint::normal(p, [normal[0], normal[2], normal[1]])
        })
        .collect()
}

/// A sphere of `n` oriented points about `centre`, its poles on the y axis.
fn sphere(centre: [f64; 3], radius: f64, n: usize) -> Vec<Constraint<3>> {
    shapes::fibonacci_sphere(n)
        .into_iter()
        .map(|[x, y, z]| {
            let d = [x, z, y];
            Constraint::normal(core::array::from_fn(|k| centre[k] + radius * d[k]), d)
        })
        .collect()
}

/// One figure: draws it into the gallery (its PNG, models and measured facts).
type Figure = fn(&mut Gallery) -> Result<(), Failure>;

pub(crate) fn run(args: &GalleryArgs, quiet: bool) -> Result<(), Failure> {
    let start = Instant::now();
    std::fs::create_dir_all(&args.output)
        .map_err(|e| bad(format!("{}: {e}", args.output.display())))?;
    let mut g = Gallery {
        dir: &args.output,
        size: args.size.clamp(16, 2048),
        entries: Vec::new(),
    };
    let figures: [(&str, Figure); 11] = [
        ("fig1", figure_1),
        ("fig2", figure_2),
        ("fig3-fig6", figures_3_and_6),
        ("fig4", figure_4),
        ("fig5", figure_5),
        ("fig7", figure_7),
        ("fig8", figure_8),
        ("fig9", figure_9),
        ("fig10", figure_10),
        ("yngve-fig3", yngve_turk_figure_3),
        ("index", write_index),
    ];
    let bar = indicatif::ProgressBar::new(figures.len() as u64);
    if quiet {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} figures, last {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    for (name, draw) in figures {
        draw(&mut g)?;
        bar.inc(1);
        bar.set_message(name);
    }
    bar.finish_and_clear();
    if !quiet {
        eprintln!(
            "wrote {} figures to {} in {:.1} s",
            g.entries.len(),
            args.output.display(),
            start.elapsed().as_secs_f64()
        );
    }
    Ok(())
}

/// Figure 1: four zero-valued and one positive constraint; then three more zero-valued.
fn figure_1(g: &mut Gallery) -> Result<(), Failure> {
    let mut c: Vec<Constraint<2>> = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]]
        .map(Constraint::boundary)
        .to_vec();
    c.push(Constraint::interior([0.0, 0.0], 1.0));
    let left = fit(c.clone())?;
    c.extend([[1.2, 1.0], [-0.3, -1.4], [-1.3, 0.9]].map(Constraint::boundary));
    let right = fit(c)?;
    g.save("fig1-left", &left)?;
    g.save("fig1-right", &right)?;
    let facts =
        json!({"boundary_residual": boundary_residual(&left).max(boundary_residual(&right))});
    let image = pair(&g.plot(&left)?, &g.plot(&right)?)?;
    g.add("fig1", "Fig. 1: a curve through four zero-valued constraints around a positive one; refined by three more.", &image, facts)
}

/// Figure 2: the tetrahedron blob; a branching object from prisms.
fn figure_2(g: &mut Gallery) -> Result<(), Failure> {
    let blob = fit(shapes::tetrahedron_blob())?;
    let tree = fit(shapes::branching(1))?;
    g.save("fig2-left", &blob)?;
    g.save("fig2-right", &tree)?;
    let facts = json!({"left": g.topology(&blob)?, "right": g.topology(&tree)?});
    let image = pair(&g.one(&blob)?, &g.one(&tree)?)?;
    g.add("fig2", "Fig. 2: zero-valued constraints at a tetrahedron's corners around a positive one; a branching shape from prisms.", &image, facts)
}

/// Figures 3 and 6: a polygonal surface and the implicit surface through its vertices with
/// their normals (the built-in cow stands in for the paper's fist and object).
fn figures_3_and_6(g: &mut Gallery) -> Result<(), Failure> {
    let mesh = rbf_mesh::read_mesh_bytes(Path::new("spot.obj"), SPOT).map_err(bad)?;
    let settings = rbf_convert::NormalSettings {
        max_vertices: 800,
        ..Default::default()
    };
    let (cow, _) = rbf_convert::convert_normals(&mesh, &settings, |_| {}).map_err(bad)?;
    g.save("fig3-fig6", &cow)?;
    let (lo, hi) = mesh.bounding_box();
    let camera = Camera::orbit(lo, hi, 215.0, 20.0, g.size, g.size);
    let image = mesh_and_model(&mesh, &cow, &camera, rbf_render::MeshStyle::Flat)?;
    let facts = json!({"vertices_used": cow.constraints.len(), "surface": g.topology(&cow)?});
    g.add("fig3-fig6", "Figs. 3 and 6: a polygonal surface (left) and the implicit surface through 800 of its vertices and their normals (right).", &image, facts)
}

/// Figure 4: exterior constraints around two, then more, zero-valued constraints.
fn figure_4(g: &mut Gallery) -> Result<(), Failure> {
    let ring: Vec<Constraint<2>> = (0..8)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 8.0;
            Constraint::exterior([2.5 * a.cos(), 2.5 * a.sin()], -1.0)
        })
        .collect();
    let mut c = ring.clone();
    c.extend([[-0.8, 0.0], [0.8, 0.0]].map(Constraint::boundary));
    let left = fit(c)?;
    let mut c = ring;
    let six = [
        [-1.0, 0.0],
        [0.0, 0.6],
        [1.0, 0.2],
        [0.4, -0.9],
        [-0.5, -0.5],
        [0.5, 1.2],
    ];
    c.extend(six.map(Constraint::boundary));
    let right = fit(c)?;
    g.save("fig4-left", &left)?;
    g.save("fig4-right", &right)?;
    let facts = json!({"boundary_residual": boundary_residual(&left).max(boundary_residual(&right)), "inside_between_the_two": left.interpolant.value(&[0.0, 0.0]) > 0.0});
    let image = pair(&g.plot(&left)?, &g.plot(&right)?)?;
    g.add("fig4", "Fig. 4: eight exterior constraints around two zero-valued constraints (an ellipse-like curve), and around six.", &image, facts)
}

/// Figure 5: boundary and normal constraints; one normal (north-west) turned.
fn figure_5(g: &mut Gallery) -> Result<(), Failure> {
    let normals = |nw: [f64; 2]| -> Vec<Constraint<2>> {
        vec![
            Constraint::normal([1.0, 0.0], [1.0, 0.0]),
            Constraint::normal([0.0, 1.0], [0.0, 1.0]),
            Constraint::normal([-1.0, 0.0], [-1.0, 0.0]),
            Constraint::normal([0.0, -1.0], [0.0, -1.0]),
            Constraint::normal([-FRAC_1_SQRT_2, FRAC_1_SQRT_2], nw),
        ]
    };
    let left = fit(normals([-1.0, 1.0]))?;
    let right = fit(normals([-1.0, -0.3]))?;
    g.save("fig5-left", &left)?;
    g.save("fig5-right", &right)?;
    let facts =
        json!({"boundary_residual": boundary_residual(&left).max(boundary_residual(&right))});
    let image = pair(&g.plot(&left)?, &g.plot(&right)?)?;
    g.add("fig5", "Fig. 5: the same boundary and normal constraints, with the north-west normal turned (right).", &image, facts)
}

/// Figure 7: the sculpting start and the torus sculpted from it by a script of edits.
fn figure_7(g: &mut Gallery) -> Result<(), Failure> {
    let start = rbf_sculpt::Session::new().map_err(bad)?;
    let mut session = rbf_sculpt::Session::new().map_err(bad)?;
    let script = rbf_sculpt::parse_script(rbf_sculpt::TORUS_SCRIPT).map_err(bad)?;
    for e in &script {
        session.apply(e).map_err(bad)?;
    }
    let (a, b) = (start.model(), session.model());
    g.save("fig7-left", &a)?;
    g.save("fig7-right", &b)?;
    let facts = json!({"left": g.topology(&a)?, "right": g.topology(&b)?, "edits": script.len()});
    let image = pair(&g.one(&a)?, &g.one(&b)?)?;
    g.add("fig7", "Fig. 7: the sculpting start (four boundary constraints in a cube of exterior ones) and a torus sculpted from it by a script of edits.", &image, facts)
}

/// Figure 8: changing a normal constraint.
fn figure_8(g: &mut Gallery) -> Result<(), Failure> {
    let mut session = rbf_sculpt::Session::new().map_err(bad)?;
    let top = session.add_boundary([0.0, 1.3, 0.0]).map_err(bad)?;
    let before = session.model();
    let handle = session.add_normal(top).map_err(bad)?;
    session.move_normal(handle, [0.35, 1.4, 0.0]).map_err(bad)?;
    let after = session.model();
    g.save("fig8-left", &before)?;
    g.save("fig8-right", &after)?;
    let facts = json!({"left": g.topology(&before)?, "right": g.topology(&after)?});
    let image = pair(&g.one(&before)?, &g.one(&after)?)?;
    g.add(
        "fig8",
        "Fig. 8: a surface before and after its normal constraint at the top is pulled sideways.",
        &image,
        facts,
    )
}

/// Figure 9: three tori and their soft union by constraint selection.
fn figure_9(g: &mut Gallery) -> Result<(), Failure> {
    let tori: Vec<Model<3>> = [[-1.4, 0.0, 0.0], [0.0, 0.0, 0.0], [1.4, 0.0, 0.0]]
        .iter()
        .map(|&c| fit(torus(c, 300)))
        .collect::<Result<_, _>>()?;
    let refs: Vec<&Model<3>> = tori.iter().collect();
    let (blend, report) = rbf_convert::blend(&refs).map_err(bad)?;
    g.save("fig9-right", &blend)?;
    let objects: Vec<Object> = (0..3).map(|i| Object::new(Csg::Model(i), i)).collect();
    let look = RenderSettings {
        shadows: true,
        ..Default::default()
    };
    let left = g.shoot(&refs, &objects, &look)?;
    let facts = json!({"blend": g.topology(&blend)?, "kept": report.kept, "total": report.total});
    let image = pair(&left, &g.one(&blend)?)?;
    g.add("fig9", "Fig. 9: three overlapping tori (left) and their soft union by constraint selection (right).", &image, facts)
}

/// Figure 10: two surfaces with shadows and reflections; CSG intersection and subtraction.
fn figure_10(g: &mut Gallery) -> Result<(), Failure> {
    let a = fit(sphere([-0.6, 0.0, 0.0], 0.8, 200))?;
    let b = fit(torus([0.7, 0.0, 0.0], 300))?;
    g.save("fig10-a", &a)?;
    g.save("fig10-b", &b)?;
    let mut objects: Vec<Object> = (0..2).map(|i| Object::new(Csg::Model(i), i)).collect();
    objects.iter_mut().for_each(|o| o.reflectivity = 0.35);
    let look = RenderSettings {
        shadows: true,
        reflections: 2,
        ..Default::default()
    };
    let left = g.shoot(&[&a, &b], &objects, &look)?;
    let c = fit(sphere([0.4, 0.0, 0.0], 0.8, 200))?;
    let meet = Csg::Intersection(vec![Csg::Model(0), Csg::Model(1)]);
    let cut = Csg::Difference(Box::new(Csg::Model(0)), Box::new(Csg::Model(1)));
    let look = RenderSettings {
        shadows: true,
        ..Default::default()
    };
    let middle = g.shoot(&[&a, &c], &[Object::new(meet, 1)], &look)?;
    let right = g.shoot(&[&a, &c], &[Object::new(cut, 0)], &look)?;
    let image = pair(&pair(&left, &middle)?, &right)?;
    g.add("fig10", "Fig. 10: two implicit surfaces with shadows and reflections; the intersection and the difference of two spheres.", &image, json!({}))
}

/// Yngve & Turk (2002), Figure 3: the iterative conversion in 2D on a teapot silhouette, steps
/// 1, 2, 3 and the last, the goal in grey under each curve.
fn yngve_turk_figure_3(g: &mut Gallery) -> Result<(), Failure> {
    let bounds = ([-1.7, -1.2], [1.9, 1.2]);
    let settings = rbf_convert::IterativeSettings {
        resolution: 96,
        initial_constraints: 12,
        max_iterations: 6,
        ..Default::default()
    };
    let mut steps: Vec<(Model<2>, f64, f64)> = Vec::new();
    rbf_convert::convert_iterative_2d(shapes::teapot_silhouette, bounds, &settings, |it, model| {
        steps.push((model.clone(), it.max_error, it.rms_error))
    })
    .map_err(|e| match e {
        rbf_convert::ConvertError::Fit(f) => Failure::fit("teapot", &f),
        other => bad(other),
    })?;
    let last = steps.len().saturating_sub(1);
    let mut strip: Option<Image> = None;
    for (k, &step) in [0, 1, 2, last].iter().enumerate() {
        let Some((model, _, _)) = steps.get(step.min(last)) else {
            continue;
        };
        g.save(&format!("yngve-fig3-step{}", k + 1), model)?;
        let plot = PlotSettings {
            width: g.size,
            height: g.size * 2 / 3,
            bounds: Some(bounds),
            ..Default::default()
        };
        let mut panel =
            plot_curve(&model.interpolant.view(), &model.constraints, &plot).map_err(bad)?;
        panel.darken_region(bounds, 0.82, shapes::teapot_silhouette);
        strip = Some(match strip {
            Some(s) => pair(&s, &panel)?,
            None => panel,
        });
    }
    let strip = strip.ok_or_else(|| bad("the 2D conversion ran no iteration"))?;
    let errors: Vec<Value> = steps
        .iter()
        .map(|(m, max, rms)| json!({"max": max, "rms": rms, "constraints": m.constraints.len()}))
        .collect();
    g.add("yngve-fig3", "Yngve & Turk, Fig. 3: iterative refinement in 2D, steps 1, 2, 3 and the last; the goal in grey, constraints marked.", &strip, json!({"steps": errors}))
}

/// `gallery.json` (what each figure measured) and `index.html` (the figures with captions).
fn write_index(g: &mut Gallery) -> Result<(), Failure> {
    let summary = json!({"figures": g.entries});
    write_atomically(
        &g.dir.join("gallery.json"),
        serde_json::to_string_pretty(&summary)
            .unwrap_or_default()
            .as_bytes(),
    )?;
    let mut html = String::from(
        "<!doctype html>\n<meta charset=\"utf-8\">\n<title>rbf gallery</title>\n<h1>Modelling with implicit surfaces that interpolate (Turk &amp; O'Brien 2002), recomputed</h1>\n",
    );
    for e in &g.entries {
        let _ = writeln!(
            html,
            "<figure><img src=\"{0}.png\" alt=\"{0}\"><figcaption>{1}</figcaption></figure>",
            e["figure"].as_str().unwrap_or(""),
            e["caption"].as_str().unwrap_or("")
        );
    }
    write_atomically(&g.dir.join("index.html"), html.as_bytes())
}
