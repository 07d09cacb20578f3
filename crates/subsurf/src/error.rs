//! Typed errors. Bad input ([`MeshError`], [`Error::Parse`]) is kept apart from internal bugs
//! ([`Error::Internal`]).

/// A problem with the content of a mesh, naming the element at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A face has fewer than three vertices.
    #[error("face {face} has {count} vertices (at least 3 are needed)")]
    FaceTooSmall {
        /// The face.
        face: usize,
        /// Its number of vertices.
        count: u32,
    },
    /// A face refers to a vertex that does not exist.
    #[error("face {face}, corner {corner}: vertex index {index} is out of range (the mesh has {count} vertices)")]
    VertexIndexOutOfRange {
        /// The face.
        face: usize,
        /// The corner within the face.
        corner: usize,
        /// The vertex index given.
        index: u32,
        /// The number of vertices of the mesh.
        count: usize,
    },
    /// `face_counts` and `face_indices` disagree.
    #[error("face counts add up to {expected} indices but {found} are given")]
    FaceIndexCountMismatch {
        /// The sum of the face counts.
        expected: usize,
        /// The length of the index list.
        found: usize,
    },
    /// A position is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate {value}")]
    NonFiniteCoordinate {
        /// The vertex.
        vertex: usize,
        /// The offending coordinate.
        value: f32,
    },
    /// A face-varying index is out of range, or the index buffer has the wrong length.
    #[error("face-varying data: {reason}")]
    FaceVarying {
        /// What is wrong.
        reason: String,
    },
    /// A crease tag names vertices that are not joined by an edge.
    #[error("crease tag {tag}: vertices {v0} and {v1} are not joined by an edge")]
    CreaseEdgeMissing {
        /// The crease's index in [`crate::Mesh::creases`].
        tag: usize,
        /// First vertex of the pair.
        v0: u32,
        /// Second vertex of the pair.
        v1: u32,
    },
    /// A sharpness edit ([`crate::limit::SharpnessEdit`]) names an element that does not
    /// exist or a value that is not a sharpness.
    #[error("sharpness edit {edit}: {reason}")]
    BadSharpnessEdit {
        /// The edit's index in the list given.
        edit: usize,
        /// What is wrong, naming the element or the value.
        reason: String,
    },
    /// A tag refers to an element that does not exist.
    #[error("{kind} tag {tag}: index {index} is out of range (there are {count})")]
    TagIndexOutOfRange {
        /// The tag's kind: `crease`, `corner` or `hole`.
        kind: &'static str,
        /// The tag's index in the mesh's list of that kind (`creases`, `corners`, `holes`).
        tag: usize,
        /// The index given.
        index: u32,
        /// How many elements the index may name (vertices, or faces for a hole).
        count: usize,
    },
    /// A tag has a NaN sharpness.
    #[error("{kind} tag {tag}: sharpness is NaN")]
    NanSharpness {
        /// The tag's kind: `crease` or `corner`.
        kind: &'static str,
        /// The tag's index in the mesh's `creases` or `corners`.
        tag: usize,
    },
    /// A construction needs a clean, closed quad manifold and the mesh is not one.
    #[error("{construction} needs {requirement}: {details}")]
    Unsupported {
        /// The construction refused (e.g. the p-rep).
        construction: &'static str,
        /// What it needs of the mesh.
        requirement: &'static str,
        /// Where the mesh falls short.
        details: String,
    },
    /// Loop subdivision was asked of a mesh with a face that is not a triangle (the first
    /// such face), as OpenSubdiv refuses it.
    #[error("Loop subdivision needs triangles only: face {face} has {corners} vertices")]
    NotTriangle {
        /// The face (0-based).
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// A caller's buffer does not have the length the operation needs.
    #[error("{what}: {found} values given, {expected} expected")]
    LengthMismatch {
        /// The buffer at fault.
        what: &'static str,
        /// The length needed.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// The requested output would not fit in memory.
    #[error("{what} would need about {human}, more than the limit of {limit_human}")]
    TooLarge {
        /// The output asked for.
        what: String,
        /// Its estimated size in bytes (saturated at `u64::MAX`; `human` holds the true size).
        bytes: u64,
        /// The same size, human-readable.
        human: String,
        /// The limit, human-readable.
        limit_human: String,
    },
}

/// Bad tessellation input ([`crate::tess`]), naming the value and where it came from.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TessError {
    /// A tessellation rate outside `1..=4096`.
    #[error("{origin}: rate {rate} of edge {v0}-{v1} is not in 1..=4096")]
    RateOutOfRange {
        /// Where the rate came from (`--tess`, `file:line`, a policy).
        origin: String,
        /// The edge's first vertex.
        v0: u32,
        /// The edge's second vertex.
        v1: u32,
        /// The rate given or needed.
        rate: u64,
    },
    /// A length, tolerance or pixel size that is not a positive finite number.
    #[error("{origin}: {what} {value} is not a positive finite number")]
    NotPositive {
        /// Where the value came from (a flag, a policy).
        origin: String,
        /// What the value is (`tolerance`, `maximum edge length`, `pixels`).
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// An edge-rates line naming two vertices that no edge joins.
    #[error("{origin}: vertices {v0} and {v1} are not joined by an edge of the mesh")]
    NoSuchEdge {
        /// `file:line`.
        origin: String,
        /// First vertex named.
        v0: u64,
        /// Second vertex named.
        v1: u64,
    },
    /// A malformed edge-rates line.
    #[error("{origin}: {reason}")]
    BadLine {
        /// `file:line`.
        origin: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A screen-space size without a camera to measure it.
    #[error("{origin}: a screen-space size needs a camera (--screen WxH and --view)")]
    NoCamera {
        /// The flag or policy asking for it.
        origin: String,
    },
    /// Curve measures that are not those of the mesh's rate curves.
    #[error(
        "{origin}: {found} curve measures for the {expected} rate curves of this mesh \
         (curves or measures of another mesh?)"
    )]
    MeasureMismatch {
        /// The policy asking for them.
        origin: String,
        /// Rate curves of the mesh.
        expected: usize,
        /// Measures given.
        found: usize,
    },
    /// A tolerance the end caps cannot meet at the deepest isolation level.
    #[error(
        "{origin}: tolerance {tolerance:e} is out of reach: the end caps of base face {face} \
         stay about {estimate:.1e} of the diagonal off the limit surface at isolation {level} \
         (the deepest), and the tolerance needs them within {budget:e}"
    )]
    ToleranceUnreachable {
        /// The policy asking for it.
        origin: String,
        /// The tolerance asked for.
        tolerance: f32,
        /// The end caps' share of it.
        budget: f32,
        /// The first base face out of reach.
        face: usize,
        /// Its end caps' estimated distance at `level`, a fraction of the diagonal.
        estimate: f32,
        /// The deepest isolation level.
        level: u32,
    },
}

/// A limit-surface query `(face, u, v)` outside the surface's domain, naming the query (its
/// 0-based index in the list given) and the value at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QueryError {
    /// The face does not exist.
    #[error("query {query}: face {face} does not exist (there are {count} faces)")]
    NoSuchFace {
        /// The query's index.
        query: usize,
        /// The face given.
        face: u64,
        /// How many faces there are (base triangles for Loop, ptex faces otherwise).
        count: usize,
    },
    /// A parameter that is NaN or infinite.
    #[error("query {query}: face {face} at (u, v) = ({u}, {v}): parameters must be finite")]
    NotFinite {
        /// The query's index.
        query: usize,
        /// The face.
        face: u64,
        /// `u` given.
        u: f64,
        /// `v` given.
        v: f64,
    },
    /// `(u, v)` off a triangle's domain `u, v ≥ 0`, `u + v ≤ 1` (Loop).
    #[error("query {query}: face {face} at (u, v) = ({u}, {v}) is outside the triangle (u, v >= 0, u + v <= 1)")]
    OutsideTriangle {
        /// The query's index.
        query: usize,
        /// The face.
        face: u64,
        /// `u` given.
        u: f64,
        /// `v` given.
        v: f64,
    },
    /// `(u, v)` off a ptex face's square `[0, 1]²`.
    #[error("query {query}: ptex face {face} at (u, v) = ({u}, {v}) is outside [0, 1] x [0, 1]")]
    OutsideSquare {
        /// The query's index.
        query: usize,
        /// The face.
        face: u64,
        /// `u` given.
        u: f64,
        /// `v` given.
        v: f64,
    },
}

/// Every error the library returns.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A malformed file: line number (1-based) and what is wrong with it.
    #[error("line {line}: {reason}")]
    Parse {
        /// The line (1-based).
        line: usize,
        /// What is wrong with it.
        reason: String,
    },
    /// A malformed glTF file: where in it (`GLB header`, `accessors[3]`,
    /// `meshes[0].primitives[1]`, ...) and what is wrong there.
    #[error("glTF {location}: {reason}")]
    Gltf {
        /// The part of the file at fault, as a glTF JSON path.
        location: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A malformed USD file: the file, the prim and the attribute at fault (empty when the
    /// fault is in the file as a whole), and what is wrong there.
    #[error("USD {file}{}{prim}{}{attribute}: {reason}", if prim.is_empty() { "" } else { ": " }, if attribute.is_empty() { "" } else { "." })]
    Usd {
        /// The file (as given to the reader; `<bytes>` when read from memory).
        file: String,
        /// The prim path, e.g. `/World/Body`.
        prim: String,
        /// The attribute name, e.g. `faceVertexIndices`.
        attribute: String,
        /// What is wrong with it.
        reason: String,
    },
    /// Bad mesh content.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// Bad tessellation input.
    #[error(transparent)]
    Tess(#[from] TessError),
    /// A limit-surface query outside the surface's domain.
    #[error(transparent)]
    Query(#[from] QueryError),
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
