//! Why a mesh could not be made, read or written.

use std::path::PathBuf;

/// Where in a file something went wrong.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// A 1-based line of a text file.
    Line(usize),
    /// A byte offset in a binary file.
    Byte(u64),
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Location::Line(l) => write!(f, "line {l}"),
            Location::Byte(b) => write!(f, "byte {b}"),
        }
    }
}

/// A mesh error, naming the file and place, or the triangle or vertex.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MeshError {
    /// The mesh has no triangles.
    #[error("the mesh has no triangles")]
    Empty,
    /// A vertex has a NaN or infinite coordinate.
    #[error("vertex {vertex} has a coordinate that is not a finite number")]
    NonFinite {
        /// 0-based vertex index.
        vertex: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {index}, but there are {vertices} vertices")]
    IndexOutOfRange {
        /// 0-based triangle index.
        triangle: usize,
        /// The 0-based vertex index the triangle names, ≥ `vertices`.
        index: usize,
        /// How many vertices the mesh has.
        vertices: usize,
    },
    /// Inconsistent parts (e.g. normals for a different number of vertices).
    #[error("{0}")]
    Invalid(String),
    /// A file could not be parsed.
    #[error("{}: {location}: {message}", file.display())]
    Parse {
        /// Path of the file that failed to parse, as the caller gave it.
        file: PathBuf,
        /// The line (text formats) or byte offset (binary formats) where parsing stopped.
        location: Location,
        /// What is wrong there, as a phrase for the user.
        message: String,
    },
    /// A file parsed, but the mesh in it is invalid.
    #[error("{}: {source}", file.display())]
    InFile {
        /// Path of the file, as the caller gave it.
        file: PathBuf,
        /// Why [`crate::TriMesh::new`] refused the parsed vertices and triangles.
        #[source]
        source: Box<MeshError>,
    },
    /// The operating system refused a read or write.
    #[error("{}: {source}", file.display())]
    Io {
        /// Path of the file being read or written, as the caller gave it.
        file: PathBuf,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// The extension names no format we know.
    #[error("{}: unknown mesh format (use .obj, .ply or .stl)", file.display())]
    UnknownFormat {
        /// Path whose extension is not .obj, .ply or .stl.
        file: PathBuf,
    },
}
