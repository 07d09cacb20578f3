//! Minimal NPY (format version 1.0) writer for little-endian `f64` arrays in C order, used to
//! export the bi-5 control points `(faces, 6, 6, 3)`.

use std::io::Write;

/// Writes `data` (row-major, `shape.iter().product()` values) as an `.npy` array of `<f8`.
pub fn write_npy<W: Write>(mut w: W, data: &[f64], shape: &[usize]) -> std::io::Result<()> {
    let count: usize = shape.iter().product();
    if count != data.len() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!(
                "npy: shape {shape:?} needs {count} values, {} given",
                data.len()
            ),
        ));
    }
    let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    let shape_txt = if shape.len() == 1 {
        format!("({},)", dims[0])
    } else {
        format!("({})", dims.join(", "))
    };
    let mut header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape_txt}, }}");
    // magic (6) + version (2) + header length (2) + header + '\n' is a multiple of 64.
    let unpadded = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - unpadded % 64) % 64));
    header.push('\n');
    w.write_all(b"\x93NUMPY\x01\x00")?;
    w.write_all(&(header.len() as u16).to_le_bytes())?;
    w.write_all(header.as_bytes())?;
    let mut buf = Vec::with_capacity(8 * data.len());
    for x in data {
        buf.extend_from_slice(&x.to_le_bytes());
    }
    w.write_all(&buf)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_is_aligned_and_parsable() {
        let mut out = Vec::new();
        write_npy(&mut out, &[1.0, -2.5], &[1, 2]).unwrap();
        assert_eq!(&out[..8], b"\x93NUMPY\x01\x00");
        let hl = u16::from_le_bytes([out[8], out[9]]) as usize;
        assert_eq!((10 + hl) % 64, 0);
        let header = std::str::from_utf8(&out[10..10 + hl]).unwrap();
        assert!(header.contains("'shape': (1, 2)") && header.ends_with('\n'));
        let body = &out[10 + hl..];
        assert_eq!(f64::from_le_bytes(body[8..16].try_into().unwrap()), -2.5);
        assert!(write_npy(&mut Vec::new(), &[1.0], &[2]).is_err());
    }
}
