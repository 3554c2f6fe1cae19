//! The server's HTTP/1.1 connections: one thread per connection, requests
//! parsed by `httparse`, responses with a known length, keep-alive.
//!
//! Why not a server crate's connection pool: `tiny_http` 0.12 hands each
//! connection to a pooled thread that serves it until the browser closes it,
//! and its pool can queue a new connection behind busy threads when two
//! arrive together. Chromium opens six connections at once for a page, keeps
//! them alive, and so left the last stylesheets of `spintop book`'s first
//! page pending forever in about one load in three. Here every connection
//! has its own thread from the moment it is accepted, and an idle one is
//! closed after [`IDLE`].
//!
//! Slow clients: a request must arrive whole, head and body, within the
//! request time from its first byte (however slowly the bytes come), else
//! [`ReadError::TooSlow`]; and each connection keeps a [`Watch`] saying
//! whether it is idle, arriving, being answered or being written, and
//! since when, so that the server can drop the one idle or slow for longest
//! when all its connections are taken.

use std::io::{self, BufRead, BufReader, Read, Write};
use std::net::{Shutdown, TcpStream};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// How long a kept-alive connection may sit idle (and how long a write may
/// block) before it is closed.
pub const IDLE: Duration = Duration::from_secs(30);

/// The request time of a new [`Connection`] (see
/// [`Connection::set_request_time`]).
const REQUEST_TIME: Duration = Duration::from_secs(10);

/// The longest request head (request line and headers) accepted.
const HEAD_BYTES: usize = 16 * 1024;

/// The most headers a request may have.
const HEADERS: usize = 64;

/// One request, its body read (or refused before reading, see [`Body`]).
#[derive(Debug)]
pub struct Request {
    /// `GET`, `HEAD`, `POST`, …
    pub method: String,
    /// The target as sent, query included.
    pub url: String,
    headers: Vec<(String, String)>,
    /// The body, if it was read.
    pub body: Body,
    /// Whether the connection stays open after the answer.
    pub keep_alive: bool,
}

/// A request's body.
#[derive(Debug)]
pub enum Body {
    /// Read in full (empty for a request without one).
    Read(Vec<u8>),
    /// Longer than the limit: not read, and the connection is closed after
    /// the answer.
    TooLong,
    /// Sent chunked: not supported, not read; the connection is closed.
    Chunked,
}

impl Request {
    /// The value of header `name` (case-insensitive), if present.
    pub fn header(&self, name: &str) -> Option<&str> {
        values(&self.headers, name).next()
    }

    /// Every value of header `name` (case-insensitive), in order.
    pub fn headers<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a str> + 'a {
        values(&self.headers, name)
    }
}

/// Every value of header `name` (case-insensitive) among `headers`, in order.
pub fn values<'a, 'n>(
    headers: &'a [(String, String)],
    name: &'n str,
) -> impl Iterator<Item = &'a str> + use<'a, 'n> {
    headers
        .iter()
        .filter(move |(k, _)| k.eq_ignore_ascii_case(name))
        .map(|(_, v)| v.as_str())
}

/// Why no request could be read.
#[derive(Debug)]
pub enum ReadError {
    /// The client closed the connection, went idle past [`IDLE`], or the
    /// socket failed: close quietly.
    Closed,
    /// Not HTTP, or a head too long: answer 400 and close.
    Malformed(String),
    /// The request did not arrive whole within the request time of its
    /// first byte: answer 408 and close.
    TooSlow,
}

/// What a connection is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Waiting for a request's first byte (kept alive, or just opened).
    Idle,
    /// A request is arriving.
    Arriving,
    /// The server is working on the answer.
    Answering,
    /// The answer is being written.
    Writing,
}

/// What a connection is doing and since when, and a handle to close it:
/// the server keeps one per open connection.
#[derive(Debug)]
pub struct Watch {
    socket: TcpStream,
    state: Mutex<(Phase, Instant)>,
}

impl Watch {
    fn set(&self, phase: Phase) {
        *self.state.lock().unwrap_or_else(|e| e.into_inner()) = (phase, Instant::now());
    }

    /// Since when the connection has been idle, arriving or being written,
    /// if it is: such a connection may be dropped for a new one. One the
    /// server is answering (a run the page waits for) may not.
    pub fn droppable_since(&self) -> Option<Instant> {
        let (phase, since) = *self.state.lock().unwrap_or_else(|e| e.into_inner());
        (phase != Phase::Answering).then_some(since)
    }

    /// Closes the connection: its thread's read or write fails at once.
    pub fn drop_now(&self) {
        let _ = self.socket.shutdown(Shutdown::Both);
    }
}

/// A connection's reading half.
pub struct Connection {
    reader: BufReader<TcpStream>,
    writer: TcpStream,
    watch: Arc<Watch>,
    request_time: Duration,
}

impl Connection {
    /// Wraps an accepted socket (blocking, with [`IDLE`] timeouts).
    pub fn new(stream: TcpStream) -> io::Result<Self> {
        stream.set_nonblocking(false)?;
        stream.set_read_timeout(Some(IDLE))?;
        stream.set_write_timeout(Some(IDLE))?;
        stream.set_nodelay(true)?;
        let writer = stream.try_clone()?;
        let watch = Arc::new(Watch {
            socket: stream.try_clone()?,
            state: Mutex::new((Phase::Idle, Instant::now())),
        });
        Ok(Self {
            reader: BufReader::new(stream),
            writer,
            watch,
            request_time: REQUEST_TIME,
        })
    }

    /// Before a connection answered without reading its request (503 from
    /// the accept loop) is closed: reads, without waiting, what has
    /// arrived of the request, and ends the writing half, so that the
    /// close sends the client no reset that could discard the answer.
    pub fn close_unread(mut self) {
        let socket = self.reader.get_ref();
        if socket.set_nonblocking(true).is_ok() {
            let mut buf = [0u8; 8192];
            let mut left: usize = 64 * 1024;
            while left > 0 {
                match self.reader.read(&mut buf) {
                    Ok(n) if n > 0 => left = left.saturating_sub(n),
                    _ => break,
                }
            }
        }
        let _ = self.writer.shutdown(Shutdown::Write);
    }

    /// The time a whole request may take to arrive from its first byte.
    pub fn set_request_time(&mut self, limit: Duration) {
        self.request_time = limit;
    }

    /// The connection's [`Watch`].
    pub fn watch(&self) -> Arc<Watch> {
        Arc::clone(&self.watch)
    }

    /// The next request, its body read up to `body_limit` bytes.
    pub fn next_request(&mut self, body_limit: usize) -> Result<Request, ReadError> {
        self.watch.set(Phase::Idle);
        let (head, deadline) = self.read_head()?;
        let mut headers = [httparse::EMPTY_HEADER; HEADERS];
        let mut parsed = httparse::Request::new(&mut headers);
        match parsed.parse(&head) {
            Ok(httparse::Status::Complete(_)) => {}
            Ok(httparse::Status::Partial) => {
                return Err(ReadError::Malformed("incomplete request head".into()));
            }
            Err(e) => return Err(ReadError::Malformed(format!("not HTTP: {e}"))),
        }
        let method = parsed.method.unwrap_or("GET").to_string();
        let url = parsed.path.unwrap_or("/").to_string();
        let version = parsed.version.unwrap_or(1);
        let headers: Vec<(String, String)> = parsed
            .headers
            .iter()
            .map(|h| {
                (
                    h.name.to_string(),
                    String::from_utf8_lossy(h.value).trim().to_string(),
                )
            })
            .collect();
        let mut request = Request {
            method,
            url,
            headers,
            body: Body::Read(Vec::new()),
            keep_alive: false,
        };
        let connection = request
            .header("Connection")
            .unwrap_or("")
            .to_ascii_lowercase();
        request.keep_alive = if version == 0 {
            connection.contains("keep-alive")
        } else {
            !connection.contains("close")
        };
        if request
            .header("Transfer-Encoding")
            .is_some_and(|v| !v.eq_ignore_ascii_case("identity"))
        {
            request.body = Body::Chunked;
            request.keep_alive = false;
            return Ok(request);
        }
        let length = match request.header("Content-Length") {
            None => 0,
            Some(v) => v
                .parse::<usize>()
                .map_err(|_| ReadError::Malformed(format!("bad Content-Length {v:?}")))?,
        };
        if length > body_limit {
            request.body = Body::TooLong;
            request.keep_alive = false;
            return Ok(request);
        }
        let mut body = vec![0; length];
        let mut filled = 0;
        while filled < length {
            self.wait_until(deadline)?;
            match self.reader.read(&mut body[filled..]) {
                Ok(0) => return Err(ReadError::Closed),
                Ok(n) => filled += n,
                Err(e) => return Err(timed_out(&e, deadline)),
            }
        }
        request.body = Body::Read(body);
        self.watch.set(Phase::Answering);
        Ok(request)
    }

    /// Sets the socket's read timeout to what is left until `deadline`
    /// (none yet: [`IDLE`]); [`ReadError::TooSlow`] once it has passed.
    fn wait_until(&self, deadline: Option<Instant>) -> Result<(), ReadError> {
        let timeout = match deadline {
            None => IDLE,
            Some(d) => d
                .checked_duration_since(Instant::now())
                .filter(|t| !t.is_zero())
                .ok_or(ReadError::TooSlow)?,
        };
        self.reader
            .get_ref()
            .set_read_timeout(Some(timeout))
            .map_err(|_| ReadError::Closed)
    }

    /// Bytes up to and including the blank line that ends a request head,
    /// and the deadline of the whole request (the request time after its
    /// first byte).
    fn read_head(&mut self) -> Result<(Vec<u8>, Option<Instant>), ReadError> {
        let mut head = Vec::new();
        let mut line_start = 0;
        let mut deadline = None;
        loop {
            self.wait_until(deadline)?;
            let buf = match self.reader.fill_buf() {
                Ok(buf) => buf,
                Err(e) => return Err(timed_out(&e, deadline)),
            };
            if buf.is_empty() {
                // EOF: between requests it is the client's goodbye.
                return if head.is_empty() {
                    Err(ReadError::Closed)
                } else {
                    Err(ReadError::Malformed("the request head was cut off".into()))
                };
            }
            if deadline.is_none() {
                deadline = Some(Instant::now() + self.request_time);
                self.watch.set(Phase::Arriving);
            }
            let room = (HEAD_BYTES + 1 - head.len()).min(buf.len());
            let (take, line_ends) = match buf[..room].iter().position(|&b| b == b'\n') {
                Some(i) => (i + 1, true),
                None => (room, false),
            };
            head.extend_from_slice(&buf[..take]);
            self.reader.consume(take);
            if head.len() > HEAD_BYTES {
                return Err(ReadError::Malformed(format!(
                    "request head longer than {} KiB",
                    HEAD_BYTES / 1024
                )));
            }
            if !line_ends {
                continue;
            }
            let line = &head[line_start..];
            if line == b"\r\n" || line == b"\n" {
                if line_start == 0 {
                    // Blank lines before a request line are allowed (RFC 9112 §2.2).
                    head.clear();
                    continue;
                }
                return Ok((head, deadline));
            }
            line_start = head.len();
        }
    }

    /// Writes one response; `head_only` for a HEAD request.
    pub fn respond(
        &mut self,
        code: u16,
        headers: &[(&str, &str)],
        body: &[u8],
        keep_alive: bool,
        head_only: bool,
    ) -> io::Result<()> {
        let mut out = format!("HTTP/1.1 {code} {}\r\n", reason(code));
        for (k, v) in headers {
            out.push_str(&format!("{k}: {v}\r\n"));
        }
        out.push_str(&format!("Content-Length: {}\r\n", body.len()));
        out.push_str(if keep_alive {
            "Connection: keep-alive\r\n\r\n"
        } else {
            "Connection: close\r\n\r\n"
        });
        let mut bytes = out.into_bytes();
        if !head_only {
            bytes.extend_from_slice(body);
        }
        self.watch.set(Phase::Writing);
        self.writer.write_all(&bytes)?;
        self.writer.flush()?;
        self.watch.set(Phase::Idle);
        Ok(())
    }
}

/// A failed read: past the deadline (a timeout once the request has begun)
/// it is [`ReadError::TooSlow`], else the connection is closed.
fn timed_out(e: &io::Error, deadline: Option<Instant>) -> ReadError {
    let timeout = matches!(
        e.kind(),
        io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut
    );
    if timeout && deadline.is_some() {
        ReadError::TooSlow
    } else {
        ReadError::Closed
    }
}

fn reason(code: u16) -> &'static str {
    match code {
        200 => "OK",
        202 => "Accepted",
        303 => "See Other",
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        408 => "Request Timeout",
        411 => "Length Required",
        413 => "Content Too Large",
        429 => "Too Many Requests",
        503 => "Service Unavailable",
        _ => "",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::net::TcpListener;

    /// A connection whose client side sends `raw` (then keeps the socket
    /// open unless `close`).
    fn pair(raw: &'static [u8], close: bool) -> (Connection, std::thread::JoinHandle<Vec<u8>>) {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let addr = listener.local_addr().unwrap();
        let client = std::thread::spawn(move || {
            let mut s = TcpStream::connect(addr).unwrap();
            s.write_all(raw).unwrap();
            if close {
                s.shutdown(std::net::Shutdown::Write).unwrap();
            }
            s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
            let mut got = Vec::new();
            let _ = s.read_to_end(&mut got);
            got
        });
        let (stream, _) = listener.accept().unwrap();
        (Connection::new(stream).unwrap(), client)
    }

    #[test]
    fn two_pipelined_requests_are_read_in_order_with_their_bodies() {
        let (mut c, client) = pair(
            b"POST /a HTTP/1.1\r\nHost: x\r\nContent-Length: 3\r\n\r\nabcGET /b?q=1 HTTP/1.1\r\nConnection: close\r\n\r\n",
            true,
        );
        let a = c.next_request(100).unwrap();
        assert_eq!((a.method.as_str(), a.url.as_str()), ("POST", "/a"));
        assert!(matches!(&a.body, Body::Read(b) if b == b"abc"));
        assert!(a.keep_alive);
        assert_eq!(a.header("host"), Some("x"));
        let b = c.next_request(100).unwrap();
        assert_eq!(b.url, "/b?q=1");
        assert!(!b.keep_alive);
        c.respond(200, &[("Content-Type", "text/plain")], b"hi", false, false)
            .unwrap();
        drop(c);
        let got = String::from_utf8(client.join().unwrap()).unwrap();
        assert!(got.starts_with("HTTP/1.1 200 OK\r\n"), "{got}");
        assert!(got.contains("Content-Length: 2\r\n") && got.ends_with("\r\n\r\nhi"));
    }

    #[test]
    fn a_body_over_the_limit_is_not_read_and_closes_the_connection() {
        let (mut c, _client) = pair(b"POST /a HTTP/1.1\r\nContent-Length: 1000\r\n\r\n", false);
        let r = c.next_request(10).unwrap();
        assert!(matches!(r.body, Body::TooLong));
        assert!(!r.keep_alive);
    }

    #[test]
    fn garbage_and_an_endless_head_are_malformed_and_eof_is_closed() {
        let (mut c, _k) = pair(b"\x00\x01 nonsense\r\n\r\n", true);
        assert!(matches!(c.next_request(10), Err(ReadError::Malformed(_))));
        let (mut c, _k) = pair(b"", true);
        assert!(matches!(c.next_request(10), Err(ReadError::Closed)));
        static LONG: [u8; 20000] = [b'a'; 20000];
        let (mut c, _k) = pair(&LONG, true);
        assert!(matches!(c.next_request(10), Err(ReadError::Malformed(_))));
    }

    #[test]
    fn http_1_0_closes_unless_asked_to_keep_alive() {
        let (mut c, _k) = pair(
            b"GET / HTTP/1.0\r\n\r\nGET / HTTP/1.0\r\nConnection: keep-alive\r\n\r\n",
            true,
        );
        assert!(!c.next_request(0).unwrap().keep_alive);
        assert!(c.next_request(0).unwrap().keep_alive);
    }
}
