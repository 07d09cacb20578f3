//! Typed errors. Bad input ([`MeshError`], [`Error::Parse`]) is kept apart from internal bugs
//! ([`Error::Internal`]).

/// A problem with the content of a mesh, naming the element at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A face has fewer than three vertices.
    #[error("face {face} has {count} vertices (at least 3 are needed)")]
    FaceTooSmall { face: usize, count: u32 },
    /// A face refers to a vertex that does not exist.
    #[error("face {face}, corner {corner}: vertex index {index} is out of range (the mesh has {count} vertices)")]
    VertexIndexOutOfRange {
        face: usize,
        corner: usize,
        index: u32,
        count: usize,
    },
    /// `face_counts` and `face_indices` disagree.
    #[error("face counts add up to {expected} indices but {found} are given")]
    FaceIndexCountMismatch { expected: usize, found: usize },
    /// A position is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate {value}")]
    NonFiniteCoordinate { vertex: usize, value: f32 },
    /// A face-varying index is out of range, or the index buffer has the wrong length.
    #[error("face-varying data: {reason}")]
    FaceVarying { reason: String },
    /// A crease tag names vertices that are not joined by an edge.
    #[error("crease tag {tag}: vertices {v0} and {v1} are not joined by an edge")]
    CreaseEdgeMissing { tag: usize, v0: u32, v1: u32 },
    /// A tag refers to an element that does not exist.
    #[error("{kind} tag {tag}: index {index} is out of range (there are {count})")]
    TagIndexOutOfRange {
        kind: &'static str,
        tag: usize,
        index: u32,
        count: usize,
    },
    /// A tag has a NaN sharpness.
    #[error("{kind} tag {tag}: sharpness is NaN")]
    NanSharpness { kind: &'static str, tag: usize },
    /// A construction needs a clean, closed quad manifold and the mesh is not one.
    #[error("{construction} needs {requirement}: {details}")]
    Unsupported {
        construction: &'static str,
        requirement: &'static str,
        details: String,
    },
    /// The requested output would not fit in memory.
    #[error(
        "{what} would need about {bytes} bytes ({human}), more than the limit of {limit_human}"
    )]
    TooLarge {
        what: String,
        bytes: u64,
        human: String,
        limit_human: String,
    },
}

/// Every error the library returns.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A malformed file: line number (1-based) and what is wrong with it.
    #[error("line {line}: {reason}")]
    Parse { line: usize, reason: String },
    /// Bad mesh content.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// A file could not be read or written.
    #[error("I/O error: {0}")]
    Io(#[from] std::io::Error),
    /// A format or option this build does not handle.
    #[error("unsupported: {0}")]
    Unsupported(String),
    /// A bug in subsurf: an invariant that should always hold did not.
    #[error("internal error (a bug in subsurf, please report): {0}")]
    Internal(String),
}

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;
