//! Checkpoint files: a fixed header (magic, format version, payload length, CRC-32 of the
//! payload) followed by the payload in `postcard` (exact little-endian `f64`s, so a restart is
//! bit-identical). A file is checked completely — magic, version, length, checksum, decoding —
//! before anything of it is used: a bad file is refused whole, never loaded half-way. The
//! payload of the previous format version ([`PREVIOUS_FORMAT_VERSION`]) is still read: the
//! run's checkpoint turns it into the present one (`mdr_sim::run::CheckpointData::read`).
//!
//! ```text
//! offset  size  field
//!      0     8  magic  b"MDRSIMCK"
//!      8     4  format version (u32 LE)
//!     12     8  payload length in bytes (u64 LE)
//!     20     4  CRC-32 (IEEE) of the payload (u32 LE)
//!     24     n  payload (postcard)
//! ```

use mdr_output::write_atomic;
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// First bytes of every checkpoint.
pub const MAGIC: &[u8; 8] = b"MDRSIMCK";
/// Version of the layout of the payload; bumped whenever it changes (1 lacked the rolling books
/// and rapier's world, 2 the springs' stiffness books and the spring states they start from, 3
/// the neighbour-list path's particles and lists, 5 the removed spheres' energy, 6 the springs'
/// stiffness energy in each contact's work books; 7 keeps the scene's fixed keys, to name what
/// changed when a restart is refused; 8 the adhesive MDR history and the adhesive work books).
pub const FORMAT_VERSION: u32 = 8;
/// The previous format version, which [`check`] accepts as well: its payload lacks the adhesive
/// MDR history and the adhesive work books, which are zero for a run that had no adhesion.
pub const PREVIOUS_FORMAT_VERSION: u32 = 7;
const HEADER_LEN: usize = 24;

/// Why a checkpoint was refused.
#[derive(Debug, Error)]
pub enum CheckpointError {
    /// The file could not be read or written.
    #[error("checkpoint {path}: {source}")]
    Io {
        /// File.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// Not a checkpoint of this program.
    #[error("{path} is not an mdr-sim checkpoint (wrong magic bytes)")]
    NotACheckpoint {
        /// File.
        path: PathBuf,
    },
    /// Written by a format version this program does not read.
    #[error(
        "checkpoint {path} has format version {found}; this program reads versions {oldest} to \
         {expected} only: rerun from the scene file with this version"
    )]
    Version {
        /// File.
        path: PathBuf,
        /// Version in the file.
        found: u32,
        /// Version this program writes (the newest it reads).
        expected: u32,
        /// Oldest version this program reads.
        oldest: u32,
    },
    /// Shorter or longer than its header says.
    #[error("checkpoint {path} is truncated or padded: header says {expected} payload bytes, file has {found}")]
    Length {
        /// File.
        path: PathBuf,
        /// Payload length from the header.
        expected: u64,
        /// Payload length found.
        found: u64,
    },
    /// The checksum does not match.
    #[error("checkpoint {path} is corrupted: CRC-32 {found:08x} does not match the header's {expected:08x}")]
    Checksum {
        /// File.
        path: PathBuf,
        /// CRC from the header.
        expected: u32,
        /// CRC computed.
        found: u32,
    },
    /// The payload does not decode.
    #[error("checkpoint {path} is corrupted: {reason}")]
    Decode {
        /// File.
        path: PathBuf,
        /// Decoder message.
        reason: String,
    },
    /// The state could not be encoded (nothing was written).
    #[error("checkpoint {path} could not be written: {reason}")]
    Encode {
        /// File.
        path: PathBuf,
        /// Encoder message.
        reason: String,
    },
    /// The payload does not fit the scene it is resumed with.
    #[error("checkpoint {path} does not belong to this scene: {reason}")]
    Incompatible {
        /// File.
        path: PathBuf,
        /// What differs.
        reason: String,
    },
}

/// Encode `payload` with its header.
pub fn encode<T: Serialize>(payload: &T) -> Vec<u8> {
    let body = postcard::to_stdvec(payload).expect("postcard encodes every serde value in memory");
    let mut out = Vec::with_capacity(HEADER_LEN + body.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    out.extend_from_slice(&(body.len() as u64).to_le_bytes());
    out.extend_from_slice(&crc32fast::hash(&body).to_le_bytes());
    out.extend_from_slice(&body);
    out
}

/// Check and decode a checkpoint of the present format version held in memory; `path` is only
/// used in messages.
pub fn decode<T: DeserializeOwned>(path: &Path, bytes: &[u8]) -> Result<T, CheckpointError> {
    match check(path, bytes)? {
        (FORMAT_VERSION, body) => decode_payload(path, body),
        (found, _) => Err(CheckpointError::Version {
            path: path.to_path_buf(),
            found,
            expected: FORMAT_VERSION,
            oldest: FORMAT_VERSION,
        }),
    }
}

/// Check a checkpoint held in memory — magic, a format version this program reads
/// ([`PREVIOUS_FORMAT_VERSION`] or [`FORMAT_VERSION`]), length, checksum — and give its format
/// version and payload; `path` is only used in messages.
pub fn check<'a>(path: &Path, bytes: &'a [u8]) -> Result<(u32, &'a [u8]), CheckpointError> {
    let path = path.to_path_buf();
    if bytes.len() < HEADER_LEN || &bytes[..8] != MAGIC {
        return Err(CheckpointError::NotACheckpoint { path });
    }
    let u32_at = |o: usize| u32::from_le_bytes(bytes[o..o + 4].try_into().expect("4 bytes"));
    let version = u32_at(8);
    if !(PREVIOUS_FORMAT_VERSION..=FORMAT_VERSION).contains(&version) {
        return Err(CheckpointError::Version {
            path,
            found: version,
            expected: FORMAT_VERSION,
            oldest: PREVIOUS_FORMAT_VERSION,
        });
    }
    let len = u64::from_le_bytes(bytes[12..20].try_into().expect("8 bytes"));
    let body = &bytes[HEADER_LEN..];
    if body.len() as u64 != len {
        return Err(CheckpointError::Length {
            path,
            expected: len,
            found: body.len() as u64,
        });
    }
    let expected = u32_at(20);
    let found = crc32fast::hash(body);
    if expected != found {
        return Err(CheckpointError::Checksum {
            path,
            expected,
            found,
        });
    }
    Ok((version, body))
}

/// Decode a checked payload ([`check`]) as `T`, the type of its format version.
pub fn decode_payload<T: DeserializeOwned>(path: &Path, body: &[u8]) -> Result<T, CheckpointError> {
    postcard::from_bytes(body).map_err(|e| CheckpointError::Decode {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })
}

/// Write a checkpoint atomically (temporary file + rename).
pub fn write<T: Serialize>(path: &Path, payload: &T) -> Result<(), CheckpointError> {
    write_atomic(path, &encode(payload)).map_err(|source| CheckpointError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Read and check a checkpoint of the present format version.
pub fn read<T: DeserializeOwned>(path: &Path) -> Result<T, CheckpointError> {
    decode(path, &read_bytes(path)?)
}

/// The bytes of a checkpoint file, unchecked ([`check`] checks them).
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, CheckpointError> {
    std::fs::read(path).map_err(|source| CheckpointError::Io {
        path: path.to_path_buf(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    struct Payload {
        step: u64,
        x: Vec<f64>,
    }

    fn sample() -> Payload {
        Payload {
            step: 42,
            x: vec![0.1, -3.0e-300, f64::MIN_POSITIVE, 1.0 / 3.0],
        }
    }

    #[test]
    fn round_trip_is_exact() {
        let p = sample();
        let back: Payload = decode(Path::new("m"), &encode(&p)).unwrap();
        assert_eq!(back, p);
        for (a, b) in back.x.iter().zip(&p.x) {
            assert_eq!(a.to_bits(), b.to_bits());
        }
    }

    #[test]
    fn every_damage_is_refused() {
        let good = encode(&sample());
        let path = Path::new("c");
        // Any single flipped payload byte: checksum.
        for i in HEADER_LEN..good.len() {
            let mut bad = good.clone();
            bad[i] ^= 0x40;
            assert!(matches!(
                decode::<Payload>(path, &bad),
                Err(CheckpointError::Checksum { .. })
            ));
        }
        // Truncation anywhere.
        for n in 0..good.len() {
            assert!(decode::<Payload>(path, &good[..n]).is_err());
        }
        let mut v = good.clone();
        v[8] = 99;
        assert!(matches!(
            decode::<Payload>(path, &v),
            Err(CheckpointError::Version { found: 99, .. })
        ));
        let mut m = good.clone();
        m[0] = b'X';
        assert!(matches!(
            decode::<Payload>(path, &m),
            Err(CheckpointError::NotACheckpoint { .. })
        ));
        // A consistent header around a payload of another type: decoding fails cleanly.
        let other = encode(&"just a string");
        assert!(matches!(
            decode::<Payload>(path, &other),
            Err(CheckpointError::Decode { .. })
        ));
    }
}
