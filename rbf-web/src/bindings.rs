//! The studio as JavaScript sees it (wasm-bindgen): one object whose methods take and return
//! numbers, strings and typed arrays. Errors arrive as thrown `Error`s with the message.

use wasm_bindgen::prelude::*;

use crate::Studio;

#[wasm_bindgen]
extern "C" {
    /// Milliseconds from the page's clock (`performance.now()`).
    #[wasm_bindgen(js_namespace = performance, js_name = now)]
    fn performance_now() -> f64;
}

/// Lattice cubes across the surface while a handle is dragged.
#[wasm_bindgen(js_name = coarseCells)]
pub fn coarse_cells() -> usize {
    crate::COARSE_CELLS
}

/// Lattice cubes across the surface when an edit is done.
#[wasm_bindgen(js_name = fineCells)]
pub fn fine_cells() -> usize {
    crate::FINE_CELLS
}

fn js_error(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// A sculpting session with its surface, for the page.
#[wasm_bindgen]
pub struct WebStudio {
    studio: Studio,
    last_solve_ms: f64,
    last_mesh_ms: f64,
    /// The history's length when the current drag began.
    gesture: Option<usize>,
}

#[wasm_bindgen]
impl WebStudio {
    /// The paper's starting blob.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Result<WebStudio, JsError> {
        Ok(Self::wrap(Studio::new().map_err(js_error)?))
    }

    /// A session on a model file's text (`name` names it in errors).
    #[wasm_bindgen(js_name = fromModel)]
    pub fn from_model(name: &str, text: &str) -> Result<WebStudio, JsError> {
        Ok(Self::wrap(
            Studio::from_model_json(name, text).map_err(js_error)?,
        ))
    }

    /// A session on a mesh file's bytes, converted by normal constraints.
    #[wasm_bindgen(js_name = fromMesh)]
    pub fn from_mesh(name: &str, bytes: &[u8]) -> Result<WebStudio, JsError> {
        Ok(Self::wrap(
            Studio::from_mesh(name, bytes).map_err(js_error)?,
        ))
    }

    fn wrap(studio: Studio) -> WebStudio {
        WebStudio {
            studio,
            last_solve_ms: 0.0,
            last_mesh_ms: 0.0,
            gesture: None,
        }
    }

    /// Applies one command line, re-meshes at `cells` cubes across when it was applied, and
    /// answers as `rbf sculpt -` does.
    pub fn command(&mut self, line: &str, cells: usize) -> String {
        let start = performance_now();
        let answer = self.studio.run(line);
        self.last_solve_ms = performance_now() - start;
        if matches!(answer, rbf_sculpt::Answer::Applied { .. }) {
            let start = performance_now();
            let meshed = self.studio.remesh(cells);
            self.last_mesh_ms = performance_now() - start;
            if let Err(e) = meshed {
                return format!(
                    "{}; the surface could not be meshed: {e}",
                    answer.line(self.last_solve_ms)
                );
            }
        }
        answer.line(self.last_solve_ms)
    }

    /// Re-meshes at `cells` cubes across.
    pub fn remesh(&mut self, cells: usize) -> Result<(), JsError> {
        let start = performance_now();
        self.studio.remesh(cells).map_err(js_error)?;
        self.last_mesh_ms = performance_now() - start;
        Ok(())
    }

    /// Vertex positions, three a vertex.
    pub fn positions(&self) -> Vec<f32> {
        self.studio.surface().positions.clone()
    }

    /// Outward unit normals, three a vertex.
    pub fn normals(&self) -> Vec<f32> {
        self.studio.surface().normals.clone()
    }

    /// Triangle vertex indices, three a triangle.
    pub fn indices(&self) -> Vec<u32> {
        self.studio.surface().indices.clone()
    }

    /// The handles, eight numbers each: item index, kind (0 boundary, 1 interior, 2 exterior,
    /// 3 normal), position x y z, base x y z (a normal handle's boundary point).
    pub fn handles(&self) -> Vec<f64> {
        self.studio
            .handles()
            .iter()
            .flat_map(|h| {
                let [x, y, z] = h.position;
                let [bx, by, bz] = h.base;
                [h.index as f64, f64::from(h.kind), x, y, z, bx, by, bz]
            })
            .collect()
    }

    /// A drag begins: its edits will undo as one.
    #[wasm_bindgen(js_name = beginGesture)]
    pub fn begin_gesture(&mut self) {
        self.gesture = Some(self.studio.begin_gesture());
    }

    /// The drag ends.
    #[wasm_bindgen(js_name = endGesture)]
    pub fn end_gesture(&mut self) {
        if let Some(mark) = self.gesture.take() {
            self.studio.end_gesture(mark);
        }
    }

    /// Starts or stops the floaters.
    #[wasm_bindgen(js_name = setFloaters)]
    pub fn set_floaters(&mut self, on: bool) {
        self.studio.set_floaters(on);
    }

    /// The floaters as discs, seven numbers each: centre x y z, outward normal x y z, radius.
    pub fn floaters(&self) -> Vec<f64> {
        self.studio
            .floaters()
            .iter()
            .flat_map(|(p, n, r)| [p[0], p[1], p[2], n[0], n[1], n[2], *r])
            .collect()
    }

    /// Where a ray first meets the surface, or nothing.
    pub fn hit(&self, origin: &[f64], direction: &[f64]) -> Option<Vec<f64>> {
        let (Ok(o), Ok(d)) = (
            <[f64; 3]>::try_from(origin),
            <[f64; 3]>::try_from(direction),
        ) else {
            return None;
        };
        self.studio.hit(o, d).ok().map(|p| p.to_vec())
    }

    /// The session as the CLI's model JSON.
    #[wasm_bindgen(js_name = modelJson)]
    pub fn model_json(&self) -> String {
        self.studio.model().to_json()
    }

    /// The current surface as a mesh file's bytes (OBJ, PLY or STL by `name`).
    pub fn export(&self, name: &str) -> Result<Vec<u8>, JsError> {
        self.studio.export(name).map_err(js_error)
    }

    /// Milliseconds the last edit's solve took.
    #[wasm_bindgen(getter, js_name = lastSolveMs)]
    pub fn last_solve_ms(&self) -> f64 {
        self.last_solve_ms
    }

    /// Milliseconds the last re-meshing took.
    #[wasm_bindgen(getter, js_name = lastMeshMs)]
    pub fn last_mesh_ms(&self) -> f64 {
        self.last_mesh_ms
    }
}
