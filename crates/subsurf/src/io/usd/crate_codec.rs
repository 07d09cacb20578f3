//! The compression of a crate file's structural sections (crate version 0.4.0 and later):
//! LZ4 blocks framed as Pixar's `TfFastCompression` frames them, and 32-bit integer lists
//! coded as Pixar's `Usd_IntegerCompression` codes them (differences to the previous value,
//! the most common difference stored once, 2-bit codes choosing 0, 1, 2 or 4 bytes for each
//! difference, then the whole buffer LZ4-compressed).

use std::collections::HashMap;

/// The largest input one LZ4 block takes (`LZ4_MAX_INPUT_SIZE`).
const LZ4_MAX_INPUT: usize = 0x7E00_0000;

/// `bytes` compressed as one `TfFastCompression` buffer: a chunk-count byte (0: one chunk),
/// then the LZ4 block; larger inputs as up to 255 chunks, each led by its compressed size.
pub(super) fn compress(bytes: &[u8]) -> Result<Vec<u8>, String> {
    if bytes.len() <= LZ4_MAX_INPUT {
        let mut out = vec![0u8];
        out.extend_from_slice(&lz4_flex::block::compress(bytes));
        return Ok(out);
    }
    let chunks = bytes.len().div_ceil(LZ4_MAX_INPUT);
    let count = u8::try_from(chunks).map_err(|_| {
        format!(
            "a section of {} bytes is too large to compress",
            bytes.len()
        )
    })?;
    let mut out = vec![count];
    for chunk in bytes.chunks(LZ4_MAX_INPUT) {
        let block = lz4_flex::block::compress(chunk);
        out.extend_from_slice(&(block.len() as i32).to_le_bytes());
        out.extend_from_slice(&block);
    }
    Ok(out)
}

/// The integer code of one difference: 0 the common value, 1 `i8`, 2 `i16`, 3 `i32`.
fn code(d: i32, common: i32) -> u8 {
    if d == common {
        0
    } else if i8::try_from(d).is_ok() {
        1
    } else if i16::try_from(d).is_ok() {
        2
    } else {
        3
    }
}

/// `values` integer-coded (uncompressed): common difference, code bytes, variable part.
pub(super) fn encode_ints(values: &[i32]) -> Vec<u8> {
    if values.is_empty() {
        return Vec::new();
    }
    let mut prev = 0i32;
    let diffs: Vec<i32> = values
        .iter()
        .map(|&v| {
            let d = v.wrapping_sub(prev);
            prev = v;
            d
        })
        .collect();
    // The most common difference (the smallest such value, for a deterministic output).
    let mut counts: HashMap<i32, usize> = HashMap::new();
    for &d in &diffs {
        *counts.entry(d).or_default() += 1;
    }
    let common = counts
        .iter()
        .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(a.0)))
        .map(|(&d, _)| d)
        .unwrap_or(0);
    let mut out = common.to_le_bytes().to_vec();
    let mut codes = vec![0u8; (diffs.len() * 2).div_ceil(8)];
    let mut ints = Vec::new();
    for (i, &d) in diffs.iter().enumerate() {
        let c = code(d, common);
        codes[i / 4] |= c << (2 * (i % 4));
        match c {
            1 => ints.extend_from_slice(&(d as i8).to_le_bytes()),
            2 => ints.extend_from_slice(&(d as i16).to_le_bytes()),
            3 => ints.extend_from_slice(&d.to_le_bytes()),
            _ => {}
        }
    }
    out.extend_from_slice(&codes);
    out.extend_from_slice(&ints);
    out
}

/// Appends `values` as a crate file stores a compressed integer list: the compressed size
/// (`u64`), then the LZ4-compressed integer coding.
pub(super) fn write_ints(out: &mut Vec<u8>, values: &[i32]) -> Result<(), String> {
    let packed = compress(&encode_ints(values))?;
    out.extend_from_slice(&(packed.len() as u64).to_le_bytes());
    out.extend_from_slice(&packed);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Decodes the integer coding (the format's description, read independently).
    fn decode(data: &[u8], n: usize) -> Vec<i32> {
        let common = i32::from_le_bytes(data[..4].try_into().unwrap());
        let codes = &data[4..4 + (n * 2).div_ceil(8)];
        let mut rest = &data[4 + codes.len()..];
        let mut prev = 0i32;
        (0..n)
            .map(|i| {
                let d = match (codes[i / 4] >> (2 * (i % 4))) & 3 {
                    0 => common,
                    1 => {
                        let v = rest[0] as i8 as i32;
                        rest = &rest[1..];
                        v
                    }
                    2 => {
                        let v = i16::from_le_bytes([rest[0], rest[1]]) as i32;
                        rest = &rest[2..];
                        v
                    }
                    _ => {
                        let v = i32::from_le_bytes(rest[..4].try_into().unwrap());
                        rest = &rest[4..];
                        v
                    }
                };
                prev = prev.wrapping_add(d);
                prev
            })
            .collect()
    }

    #[test]
    fn integer_coding_round_trips_and_matches_the_documented_example() {
        // The example of Pixar's integerCoding.cpp: differences [123, 1, 1, 100000, 0, 1, 0],
        // common value 1, codes 01 00 00 11 | 01 00 01, then i8 123, i32 100000, i8 0, i8 0.
        let v = [123, 124, 125, 100125, 100125, 100126, 100126];
        let e = encode_ints(&v);
        let mut want = 1i32.to_le_bytes().to_vec();
        want.extend_from_slice(&[0b1100_0001, 0b0001_0001, 123]);
        want.extend_from_slice(&100000i32.to_le_bytes());
        want.extend_from_slice(&[0, 0]);
        assert_eq!(e, want);
        let v: Vec<i32> = vec![i32::MIN, i32::MAX, -2, 0, -1, 40000, -40000, 7, 7, 7];
        assert_eq!(decode(&encode_ints(&v), v.len()), v);
        assert!(encode_ints(&[]).is_empty());
    }

    #[test]
    fn compressed_buffers_decompress_with_lz4() {
        let bytes: Vec<u8> = (0..5000u32).map(|i| (i % 251) as u8).collect();
        let c = compress(&bytes).unwrap();
        assert_eq!(c[0], 0);
        assert_eq!(
            lz4_flex::block::decompress(&c[1..], bytes.len()).unwrap(),
            bytes
        );
    }
}
