//! Compact result storage: JSON, deflated when large.

use flate2::{read::DeflateDecoder, write::DeflateEncoder, Compression};
use std::io::{Read, Write};

/// Results above this many bytes are stored deflated.
const COMPRESS_ABOVE: usize = 2048;

/// A result ready to store.
#[derive(Debug, Clone)]
pub struct Encoded {
    pub encoding: &'static str,
    /// Uncompressed size, bytes.
    pub size: usize,
    pub body: Vec<u8>,
}

/// Encode a JSON text for storage.
pub fn encode_result(json: &str) -> Encoded {
    if json.len() <= COMPRESS_ABOVE {
        return Encoded { encoding: "json", size: json.len(), body: json.as_bytes().to_vec() };
    }
    let mut enc = DeflateEncoder::new(Vec::with_capacity(json.len() / 4), Compression::fast());
    // Writing into a Vec cannot fail.
    enc.write_all(json.as_bytes()).expect("deflate into memory");
    let body = enc.finish().expect("deflate into memory");
    Encoded { encoding: "json+deflate", size: json.len(), body }
}

/// Decode a stored result back to JSON text.
pub fn decode_result(encoding: &str, body: &[u8]) -> Result<String, String> {
    match encoding {
        "json" => String::from_utf8(body.to_vec()).map_err(|e| e.to_string()),
        "json+deflate" => {
            let mut out = String::new();
            DeflateDecoder::new(body).read_to_string(&mut out).map_err(|e| e.to_string())?;
            Ok(out)
        }
        other => Err(format!("unknown result encoding {other}")),
    }
}
