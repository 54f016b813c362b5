//! Streaming the image into a running tev (Thomas Müller's HDR image viewer) over its TCP
//! protocol, pass after pass, as a render refines: the graphics programmer's habit from
//! pbrt and Mitsuba (`--tev`).
//!
//! Each message is little-endian: its length in bytes (u32, the length itself included),
//! its type (u8), then its fields; strings end in a zero byte. raylab sends two:
//!
//! - **create image** (type 4): grab focus (u8), name, width, height (i32), the number of
//!   channels (i32) and their names: one image with the layer R, G, B.
//! - **update image** (type 6): grab focus (u8), name, the number of channels (i32) and
//!   their names, the rectangle x, y, width, height (i32), each channel's offset and then
//!   each one's stride (i64, in floats), and the pixels (f32): here R, G, B interleaved, so
//!   the offsets are 0, 1, 2 and the strides 3.
//!
//! The pixels are the film's mean radiance, linear, as an EXR holds them: tev applies its
//! own exposure and sRGB curve.

use crate::math::Color;
use std::io::Write;
use std::net::{TcpStream, ToSocketAddrs};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// Where tev listens unless told otherwise (`tev --hostname`).
pub const TEV_ADDRESS: &str = "127.0.0.1:14158";

/// The message types raylab sends (tev's `IpcPacket::EType`).
const CREATE_IMAGE: u8 = 4;
const UPDATE_IMAGE: u8 = 6;
/// The channels sent, in this order: one RGB layer.
const CHANNELS: [&str; 3] = ["R", "G", "B"];
/// An update carries at most about this many bytes of pixels (whole rows), so that tev
/// shows the image filling in band by band and no message is very large.
const UPDATE_BYTES: usize = 1 << 20;
/// How long connecting and each write may take before tev is given up on.
const TIMEOUT: Duration = Duration::from_secs(5);

/// tev cannot be reached, or stopped listening.
#[derive(Debug, thiserror::Error)]
#[error("tev at {address}: {error}")]
pub struct TevError {
    address: String,
    error: std::io::Error,
}

/// A connection to tev, showing one image.
pub struct Tev {
    stream: TcpStream,
    address: String,
    name: String,
    width: u32,
    height: u32,
}

impl Tev {
    /// Connects to tev at `address` (HOST:PORT) and creates the image `name` of `width` ×
    /// `height` pixels there, black, shown at once.
    pub fn connect(address: &str, name: &str, width: u32, height: u32) -> Result<Tev, TevError> {
        let fail = |error| TevError {
            address: address.to_string(),
            error,
        };
        let mut last =
            std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a HOST:PORT address");
        let mut stream = None;
        for addr in address.to_socket_addrs().map_err(fail)? {
            match TcpStream::connect_timeout(&addr, TIMEOUT) {
                Ok(s) => {
                    stream = Some(s);
                    break;
                }
                Err(e) => last = e,
            }
        }
        let stream = stream.ok_or_else(|| fail(last))?;
        stream.set_write_timeout(Some(TIMEOUT)).map_err(fail)?;
        // Each message is written whole; waiting to fill a segment only delays the image.
        stream.set_nodelay(true).map_err(fail)?;
        let mut tev = Tev {
            stream,
            address: address.to_string(),
            name: name.to_string(),
            width,
            height,
        };
        let create = create_message(name, width, height);
        tev.send(&create)?;
        Ok(tev)
    }

    /// Sends the whole image, `pixels` row by row from the top (`width` × `height` of
    /// them), in bands of whole rows.
    pub fn update(&mut self, pixels: &[Color]) -> Result<(), TevError> {
        let width = self.width as usize;
        let rows = (UPDATE_BYTES / (width.max(1) * 12)).max(1);
        for (band, chunk) in pixels.chunks(width.max(1) * rows).enumerate() {
            let y = (band * rows) as u32;
            let h = (chunk.len() / width.max(1)) as u32;
            let message = update_message(&self.name, (0, y), (self.width, h), chunk);
            self.send(&message)?;
        }
        Ok(())
    }

    fn send(&mut self, message: &[u8]) -> Result<(), TevError> {
        self.stream.write_all(message).map_err(|error| TevError {
            address: self.address.clone(),
            error,
        })
    }

    /// The image's size.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }
}

/// One image to send: its width, its height and its pixels.
type Image = (u32, u32, Arc<Vec<Color>>);

/// A stream into tev on a thread of its own, for the window: sending never waits. Each
/// image replaces the one not yet sent, so tev always gets the newest and the window never
/// queues images behind a slow connection. The image is named `name` in tev and made again
/// when its size changes.
pub struct TevStream {
    images: crossbeam_channel::Sender<Image>,
    // To drop an image not yet sent in favour of a newer one.
    unsent: crossbeam_channel::Receiver<Image>,
    error: Arc<Mutex<Option<String>>>,
    address: String,
}

impl TevStream {
    /// Starts streaming to tev at `address`; it connects with the first image. `stopped`
    /// is called if the stream stops (then [`TevStream::error`] says why), so that a
    /// window can say so at once.
    pub fn start(address: &str, name: &str, stopped: impl Fn() + Send + 'static) -> TevStream {
        let (images, unsent) = crossbeam_channel::bounded::<Image>(1);
        let error = Arc::new(Mutex::new(None));
        let (rx, failed) = (unsent.clone(), Arc::clone(&error));
        let (address_, name) = (address.to_string(), name.to_string());
        let spawned = std::thread::Builder::new()
            .name("raylab-tev".into())
            .spawn(move || {
                let mut tev: Option<Tev> = None;
                for (w, h, pixels) in rx.iter() {
                    let sent = match tev.as_mut().filter(|t| t.size() == (w, h)) {
                        Some(t) => t.update(&pixels),
                        None => Tev::connect(&address_, &name, w, h)
                            .and_then(|t| tev.insert(t).update(&pixels)),
                    };
                    if let Err(e) = sent {
                        log::debug!("{e}");
                        *failed.lock().unwrap_or_else(|p| p.into_inner()) = Some(e.to_string());
                        stopped();
                        return;
                    }
                }
            });
        if let Err(e) = spawned {
            *error.lock().unwrap_or_else(|p| p.into_inner()) =
                Some(format!("tev at {address}: cannot start its thread: {e}"));
        }
        TevStream {
            images,
            unsent,
            error,
            address: address.to_string(),
        }
    }

    /// Sends `pixels` (`width` × `height`, row by row), replacing an image not yet sent.
    pub fn send(&self, width: u32, height: u32, pixels: Arc<Vec<Color>>) {
        if let Err(crossbeam_channel::TrySendError::Full(image)) =
            self.images.try_send((width, height, pixels))
        {
            let _ = self.unsent.try_recv();
            let _ = self.images.try_send(image);
        }
    }

    /// Why the stream stopped (tev not there, or closed), once it has.
    pub fn error(&self) -> Option<String> {
        self.error.lock().ok().and_then(|e| e.clone())
    }

    /// Where it streams to.
    pub fn address(&self) -> &str {
        &self.address
    }
}

/// A message of `kind` whose fields `fill` writes after the type: its length is put in
/// front once they are written.
fn message(kind: u8, fill: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
    let mut m = vec![0, 0, 0, 0, kind];
    fill(&mut m);
    let len = m.len() as u32;
    m[..4].copy_from_slice(&len.to_le_bytes());
    m
}

/// A zero-terminated string (a zero byte inside it would end it early in tev: cut there).
fn put_str(m: &mut Vec<u8>, s: &str) {
    m.extend(s.bytes().take_while(|&b| b != 0));
    m.push(0);
}

fn put_i32(m: &mut Vec<u8>, v: u32) {
    m.extend((v.min(i32::MAX as u32) as i32).to_le_bytes());
}

/// "Create image" (type 4): `name`, `width` × `height`, channels R, G, B; grabbing focus.
fn create_message(name: &str, width: u32, height: u32) -> Vec<u8> {
    message(CREATE_IMAGE, |m| {
        m.push(1);
        put_str(m, name);
        put_i32(m, width);
        put_i32(m, height);
        put_i32(m, CHANNELS.len() as u32);
        for c in CHANNELS {
            put_str(m, c);
        }
    })
}

/// "Update image" (type 6): the rectangle at `(x, y)` of `size` of `name`, its `pixels`
/// row by row, R, G, B interleaved; not grabbing focus (the user may have moved on).
fn update_message(name: &str, (x, y): (u32, u32), size: (u32, u32), pixels: &[Color]) -> Vec<u8> {
    message(UPDATE_IMAGE, |m| {
        m.push(0);
        put_str(m, name);
        put_i32(m, CHANNELS.len() as u32);
        for c in CHANNELS {
            put_str(m, c);
        }
        for v in [x, y, size.0, size.1] {
            put_i32(m, v);
        }
        for offset in 0..CHANNELS.len() as i64 {
            m.extend(offset.to_le_bytes());
        }
        for _ in CHANNELS {
            m.extend((CHANNELS.len() as i64).to_le_bytes());
        }
        m.reserve(pixels.len() * 12);
        for p in pixels {
            for v in [p.x, p.y, p.z] {
                m.extend(v.to_le_bytes());
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_create_message_is_tevs_byte_for_byte() {
        let m = create_message("ab", 2, 1);
        #[rustfmt::skip]
        let expected: Vec<u8> = vec![
            27, 0, 0, 0,            // length: the whole message, 27 bytes
            4,                      // create image
            1,                      // grab focus
            b'a', b'b', 0,          // name
            2, 0, 0, 0,             // width
            1, 0, 0, 0,             // height
            3, 0, 0, 0,             // channels
            b'R', 0, b'G', 0, b'B', 0,
        ];
        assert_eq!(m, expected);
    }

    #[test]
    fn an_update_message_is_tevs_byte_for_byte() {
        let m = update_message("a", (5, 6), (1, 1), &[Color::new(1.0, 2.0, 0.5)]);
        let mut expected: Vec<u8> = vec![0, 0, 0, 0, 6, 0, b'a', 0, 3, 0, 0, 0];
        expected.extend([b'R', 0, b'G', 0, b'B', 0]);
        for v in [5i32, 6, 1, 1] {
            expected.extend(v.to_le_bytes());
        }
        for v in [0i64, 1, 2, 3, 3, 3] {
            expected.extend(v.to_le_bytes());
        }
        for v in [1.0f32, 2.0, 0.5] {
            expected.extend(v.to_le_bytes());
        }
        let len = expected.len() as u32;
        expected[..4].copy_from_slice(&len.to_le_bytes());
        assert_eq!(m, expected);
        assert_eq!(len, 4 + 1 + 1 + 2 + 4 + 6 + 16 + 48 + 12);
    }

    #[test]
    fn nobody_listening_is_one_line_naming_the_address() {
        // A port just released: nothing listens there.
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .and_then(|l| l.local_addr())
            .map(|a| a.port())
            .unwrap();
        let address = format!("127.0.0.1:{port}");
        let e = Tev::connect(&address, "x", 4, 4).err().unwrap().to_string();
        assert!(e.starts_with(&format!("tev at {address}: ")), "{e}");
        assert_eq!(e.lines().count(), 1);
        let e = Tev::connect("no-port", "x", 4, 4)
            .err()
            .unwrap()
            .to_string();
        assert!(e.starts_with("tev at no-port: "), "{e}");
    }
}
