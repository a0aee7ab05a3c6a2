//! A deterministic attribute order for the EXR files brume writes.
//!
//! The `exr` crate keeps custom attributes in a `HashMap` and writes them in its iteration
//! order, which changes from one process to the next: two renders of the same passes would give
//! files with the same pixels but different bytes. OpenEXR leaves the order of a header's
//! attributes free, so brume sorts them by name after writing. Sorting moves bytes only within
//! the header, whose length does not change, so the offset table that follows it stays right.

/// Sorts the attributes of a single-part EXR file's header by name, in place. Returns false
/// (and leaves the bytes alone) if the header cannot be parsed as one.
pub fn sort_attributes(bytes: &mut [u8]) -> bool {
    const MULTIPART: u8 = 0x10;
    if bytes.len() < 8 || bytes[..4] != [0x76, 0x2f, 0x31, 0x01] || bytes[5] & MULTIPART != 0 {
        return false;
    }
    let Some((attributes, end)) = attributes(bytes, 8) else {
        return false;
    };
    let mut sorted: Vec<&[u8]> = attributes.iter().map(|&(a, b)| &bytes[a..b]).collect();
    sorted.sort_by_key(|a| name(a));
    let header: Vec<u8> = sorted.concat();
    bytes[8..end].copy_from_slice(&header);
    true
}

/// The byte ranges of the attributes from `at` to the header's terminating null byte, and the
/// position of that byte.
fn attributes(bytes: &[u8], mut at: usize) -> Option<(Vec<(usize, usize)>, usize)> {
    let mut out = Vec::new();
    while *bytes.get(at)? != 0 {
        let start = at;
        for _ in 0..2 {
            // The attribute's name, then its type name, each null-terminated.
            at += bytes.get(at..)?.iter().position(|&b| b == 0)? + 1;
        }
        let size = i32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?);
        at = at.checked_add(4 + usize::try_from(size).ok()?)?;
        if at > bytes.len() {
            return None;
        }
        out.push((start, at));
    }
    Some((out, at))
}

/// An attribute's name (its bytes up to the first null).
fn name(attribute: &[u8]) -> &[u8] {
    let end = attribute
        .iter()
        .position(|&b| b == 0)
        .unwrap_or(attribute.len());
    &attribute[..end]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn attr(name: &str, value: &[u8]) -> Vec<u8> {
        let mut a = format!("{name}\0string\0").into_bytes();
        a.extend((value.len() as i32).to_le_bytes());
        a.extend(value);
        a
    }

    #[test]
    fn attributes_are_sorted_and_the_rest_is_untouched() {
        let mut file = vec![0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0];
        for (n, v) in [("zeta", &b"1"[..]), ("alpha", b"22"), ("mid", b"")] {
            file.extend(attr(n, v));
        }
        file.push(0);
        file.extend([9, 8, 7]);
        let mut want = file[..8].to_vec();
        for (n, v) in [("alpha", &b"22"[..]), ("mid", b""), ("zeta", b"1")] {
            want.extend(attr(n, v));
        }
        want.extend([0, 9, 8, 7]);
        assert!(sort_attributes(&mut file));
        assert_eq!(file, want);
    }

    #[test]
    fn a_damaged_header_is_left_alone() {
        let mut file = vec![0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0];
        file.extend(b"name\0string\0");
        file.extend(1000i32.to_le_bytes());
        let before = file.clone();
        assert!(!sort_attributes(&mut file));
        assert_eq!(file, before);
        assert!(!sort_attributes(&mut [1, 2, 3]));
    }
}
