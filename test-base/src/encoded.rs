//! Small files written by hand: a baseline JPEG and a GLB container, for the loaders' tests
//! and fuzz seeds (the repository has no JPEG asset).

/// A baseline JPEG of 16 × 8 grey pixels of value 144, written by hand (the repository has
/// no JPEG asset): one quantisation table of ones, DC-only blocks (the first DC is
/// 8 · 16 = 128, category 8; the second a zero difference), every AC block an end-of-block.
#[must_use]
pub fn grey_jpeg() -> Vec<u8> {
    let mut j = vec![0xFF, 0xD8];
    // DQT: table 0, 8-bit, all ones.
    j.extend([0xFF, 0xDB, 0x00, 0x43, 0x00]);
    j.extend([1u8; 64]);
    // SOF0: 8 bits, 8 high, 16 wide, one component (id 1, 1x1 sampling, table 0).
    j.extend([
        0xFF, 0xC0, 0x00, 0x0B, 0x08, 0x00, 0x08, 0x00, 0x10, 0x01, 0x01, 0x11, 0x00,
    ]);
    // DHT DC 0: two codes of length 2 for categories 0 and 8.
    j.extend([0xFF, 0xC4, 0x00, 0x15, 0x00, 0, 2]);
    j.extend([0u8; 14]);
    j.extend([0x00, 0x08]);
    // DHT AC 0: one code of length 2 for end-of-block.
    j.extend([0xFF, 0xC4, 0x00, 0x14, 0x10, 0, 1]);
    j.extend([0u8; 14]);
    j.extend([0x00]);
    // SOS, then the scan: 01 10000000 00 | 00 00.
    j.extend([0xFF, 0xDA, 0x00, 0x08, 0x01, 0x01, 0x00, 0x00, 0x3F, 0x00]);
    j.extend([0x60, 0x00]);
    j.extend([0xFF, 0xD9]);
    j
}

/// Assembles a GLB container from a JSON chunk and a binary chunk.
#[must_use]
pub fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let pad = |n: usize| (4 - n % 4) % 4;
    let json_len = json.len() + pad(json.len());
    let bin_len = bin.len() + pad(bin.len());
    let total = 12 + 8 + json_len + 8 + bin_len;
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json_len as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json.as_bytes());
    out.extend(std::iter::repeat_n(b' ', pad(json.len())));
    out.extend((bin_len as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out.extend(std::iter::repeat_n(0u8, pad(bin.len())));
    out
}
