//! SHA-256 for the manifest (the `sha2` crate).

/// SHA-256 of `bytes` as lowercase hex (FIPS 180-4), for the manifest.
pub fn sha256_hex(bytes: &[u8]) -> String {
    let mut h = Sha256::new();
    h.update(bytes);
    h.hex()
}

/// SHA-256 (FIPS 180-4, the `sha2` crate) fed in pieces, for files streamed to disk that are
/// never whole in memory.
#[derive(Debug, Clone, Default)]
pub struct Sha256(sha2::Sha256);

impl Sha256 {
    /// The hash of nothing yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Feeds `bytes`.
    pub fn update(&mut self, bytes: &[u8]) {
        sha2::Digest::update(&mut self.0, bytes);
    }

    /// The digest as lowercase hex.
    pub fn hex(self) -> String {
        sha2::Digest::finalize(self.0).iter().map(|b| format!("{b:02x}")).collect()
    }
}
