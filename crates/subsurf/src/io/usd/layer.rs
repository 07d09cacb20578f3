//! One USD layer in memory: `.usda`, `.usdc` and `.usdz` bytes to and from the `openusd`
//! crate's spec store (`sdf::Data`), with every failure turned into [`Error::Usd`].

use super::UsdFormat;
use crate::error::{Error, Result};
use openusd::sdf::{self, AbstractData};
use std::io::Cursor;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// The crate file magic.
const CRATE_MAGIC: &[u8] = b"PXR-USDC";
/// The text layer header.
const TEXT_MAGIC: &[u8] = b"#usda";
/// The zip local file header magic.
const ZIP_MAGIC: &[u8] = b"PK\x03\x04";

/// A file-level USD error (no prim, no attribute).
pub(super) fn file_error(file: &str, reason: impl std::fmt::Display) -> Error {
    Error::Usd {
        file: file.to_string(),
        prim: String::new(),
        attribute: String::new(),
        reason: reason.to_string(),
    }
}

/// The format of USD bytes, by their magic: crate, zip or text.
pub(super) fn sniff(bytes: &[u8]) -> Option<UsdFormat> {
    if bytes.starts_with(CRATE_MAGIC) {
        Some(UsdFormat::Usdc)
    } else if bytes.starts_with(ZIP_MAGIC) {
        Some(UsdFormat::Usdz)
    } else if bytes.starts_with(TEXT_MAGIC) {
        Some(UsdFormat::Usda)
    } else {
        None
    }
}

/// Runs a step of the `openusd` crate; a panic in it (a bug there, on malformed input) is
/// reported as a file error rather than unwinding through the caller.
fn guarded<T>(
    file: &str,
    what: &str,
    f: impl FnOnce() -> std::result::Result<T, String>,
) -> Result<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(e)) => Err(file_error(file, format!("{what}: {e}"))),
        Err(_) => Err(file_error(file, format!("{what}: malformed data"))),
    }
}

/// An `openusd` error as text, its causes included.
fn msg(e: impl std::fmt::Display) -> String {
    format!("{e:#}")
}

/// Reads a whole layer into memory. The format is taken from the bytes' magic; a file whose
/// magic disagrees with its extension is read by what it is, as USD does.
pub(super) fn read(bytes: &[u8], file: &str) -> Result<sdf::Data> {
    match sniff(bytes) {
        Some(UsdFormat::Usdc) => read_crate(bytes.to_vec(), file),
        Some(UsdFormat::Usdz) => read_zip(bytes, file),
        Some(UsdFormat::Usda) => read_text(bytes, file),
        None => Err(file_error(
            file,
            "not a USD layer (no '#usda' header, crate or zip magic)",
        )),
    }
}

fn read_text(bytes: &[u8], file: &str) -> Result<sdf::Data> {
    let text = std::str::from_utf8(bytes)
        .map_err(|e| file_error(file, format!("text layer is not UTF-8: {e}")))?;
    guarded(file, "parsing the text layer", || {
        openusd::usda::parse(text).map_err(msg)
    })
}

fn read_crate(bytes: Vec<u8>, file: &str) -> Result<sdf::Data> {
    guarded(file, "reading the crate file", || {
        let data = openusd::usdc::CrateData::open(Cursor::new(bytes), true).map_err(msg)?;
        sdf::Data::from_abstract(&data).map_err(msg)
    })
}

/// A `.usdz` package: its first USD layer (the package's root layer, by the USDZ spec).
fn read_zip(bytes: &[u8], file: &str) -> Result<sdf::Data> {
    guarded(file, "reading the usdz package", || {
        let mut archive =
            openusd::usdz::Archive::from_reader(Cursor::new(bytes.to_vec())).map_err(msg)?;
        let layer = archive.read_first_layer().map_err(msg)?;
        sdf::Data::from_abstract(&layer).map_err(msg)
    })
}

/// Writes a layer in `format`: text through the `openusd` crate, crate files through
/// subsurf's own writer (`crate_write`; the crate files `openusd` 0.6 writes do not open in
/// Pixar's USD). A `.usdz` package holds one crate layer, stored and 64-byte aligned as the
/// USDZ spec asks.
pub(super) fn write(data: &sdf::Data, format: UsdFormat, file: &str) -> Result<Vec<u8>> {
    let dyn_data: &dyn AbstractData = data;
    match format {
        UsdFormat::Usda => guarded(file, "writing the text layer", || {
            Ok(openusd::usda::TextWriter::write_to_string(dyn_data)
                .map_err(msg)?
                .into_bytes())
        }),
        UsdFormat::Usdc => super::crate_write::write(data).map_err(|e| Error::Usd {
            file: file.to_string(),
            prim: e.path,
            attribute: e.field,
            reason: format!("writing the crate file: {}", e.reason),
        }),
        UsdFormat::Usdz => {
            let layer = write(data, UsdFormat::Usdc, file)?;
            guarded(file, "writing the usdz package", || {
                let mut zip = openusd::usdz::ArchiveWriter::new(Cursor::new(Vec::new()));
                zip.add_layer(&root_layer_name(file), &layer).map_err(msg)?;
                Ok(zip.finish().map_err(msg)?.into_inner())
            })
        }
    }
}

/// The name of a package's root layer: the package's file name with a `.usdc` extension.
fn root_layer_name(file: &str) -> String {
    let stem = std::path::Path::new(file)
        .file_stem()
        .and_then(|s| s.to_str())
        .filter(|s| {
            !s.is_empty()
                && s.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c))
        })
        .unwrap_or("root");
    format!("{stem}.usdc")
}
