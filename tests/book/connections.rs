//! Slow and kept-alive connections: a browser's, and an attacker's.

use super::*;
use spintop_server::MAX_CONNECTIONS;
use std::io::{Read, Write};
use std::net::TcpStream;

/// One response read off a kept-alive connection: status and body (by its
/// Content-Length), or `None` if it does not come within 10 s.
fn read_response(stream: &mut TcpStream) -> Option<(u16, String)> {
    stream
        .set_read_timeout(Some(Duration::from_secs(10)))
        .unwrap();
    let mut raw = Vec::new();
    let mut byte = [0u8; 1];
    while !raw.ends_with(b"\r\n\r\n") {
        if stream.read(&mut byte).ok()? == 0 {
            return None;
        }
        raw.push(byte[0]);
    }
    let head = String::from_utf8_lossy(&raw).into_owned();
    let code = head.split_whitespace().nth(1)?.parse().ok()?;
    let length: usize = head
        .lines()
        .find_map(|l| l.strip_prefix("Content-Length: "))?
        .trim()
        .parse()
        .ok()?;
    let mut body = vec![0; length];
    stream.read_exact(&mut body).ok()?;
    Some((code, String::from_utf8_lossy(&body).into_owned()))
}

/// A browser opens several connections at once for a page and keeps them
/// open, some without sending anything yet. Every connection must be
/// answered while the others stay open: a server that serves connections
/// one after another, or from a pool that can queue one behind kept-alive
/// ones (as `tiny_http`'s did, which hung the first page of `spintop book`
/// in Chromium about one load in three), fails here or in the browser test.
#[test]
fn connections_a_browser_keeps_open_never_hold_up_another() {
    let s = start("keepalive", limits());
    let port = s.port;
    let cookie = s.cookie();
    // Twelve connections at the same instant, each asking twice and then
    // held open until all have their answers (or have waited 10 s in vain).
    let start_line = Arc::new(std::sync::Barrier::new(12));
    let finish_line = Arc::new(std::sync::Barrier::new(12));
    let clients: Vec<_> = (0..12)
        .map(|_| {
            let (start_line, finish_line) = (Arc::clone(&start_line), Arc::clone(&finish_line));
            let cookie = cookie.clone();
            std::thread::spawn(move || {
                start_line.wait();
                let mut c = TcpStream::connect(("127.0.0.1", port)).unwrap();
                let get = format!(
                    "GET /css/book.css HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nCookie: {cookie}\r\n\r\n"
                );
                let mut answers = Vec::new();
                for _ in 0..2 {
                    c.write_all(get.as_bytes()).unwrap();
                    answers.push(read_response(&mut c));
                }
                finish_line.wait();
                answers
            })
        })
        .collect();
    // Eight idle connections beside them, as Chromium's preconnects.
    let idle: Vec<_> = (0..8)
        .map(|_| TcpStream::connect(("127.0.0.1", port)).unwrap())
        .collect();
    for client in clients {
        for answer in client.join().unwrap() {
            assert_eq!(answer, Some((200, "body {}".to_string())));
        }
    }
    drop(idle);
}

/// A page load as a browser makes it: six files at once, with the cookie;
/// how long until all six are in.
fn page_load(s: &Running) -> Duration {
    let started = Instant::now();
    let loads: Vec<_> = (0..6)
        .map(|i| {
            let (port, cookie) = (s.port, s.cookie());
            std::thread::spawn(move || {
                let path = if i == 0 { "/" } else { "/css/book.css" };
                request(port, "GET", path, &[("Cookie", &cookie)], b"").unwrap()
            })
        })
        .collect();
    for load in loads {
        let (status, text) = load.join().unwrap();
        assert_eq!(status, 200, "{text}");
    }
    started.elapsed()
}

/// F3: slowloris. Every connection the server takes sends one byte of a
/// request head a second; a page load still answers, long before the
/// request time, because the oldest slow connection is dropped for each new
/// one.
#[test]
#[ignore = "end-to-end: real time, a connection trickling for seconds"]
fn slow_connections_do_not_delay_a_page_load() {
    let s = start("slowloris", limits());
    let unloaded = page_load(&s);
    let mut slow: Vec<TcpStream> = (0..MAX_CONNECTIONS)
        .map(|_| TcpStream::connect(("127.0.0.1", s.port)).unwrap())
        .collect();
    let head = format!("GET / HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nX-Slow: ", s.port).into_bytes();
    let stop = Arc::new(AtomicBool::new(false));
    let stop_trickle = Arc::clone(&stop);
    let trickle = std::thread::spawn(move || {
        let mut sent = 0;
        while !stop_trickle.load(Ordering::Relaxed) {
            for c in &mut slow {
                let _ = c.write_all(&[head.get(sent).copied().unwrap_or(b'a')]);
            }
            sent += 1;
            std::thread::sleep(Duration::from_secs(1));
        }
    });
    // All of them have begun their requests.
    std::thread::sleep(Duration::from_millis(1500));
    let loaded = page_load(&s);
    stop.store(true, Ordering::Relaxed);
    trickle.join().unwrap();
    // Every request answered 200 (page_load checks), and well before the
    // request time (10 s) would have cut the slow ones: a server that waited
    // for that, or answered 503, fails here. The margin is wide because a
    // loaded machine (CI on 2 cores) slows both loads; speed itself is not
    // what this test measures.
    assert!(
        loaded < unloaded + Duration::from_secs(5),
        "with {MAX_CONNECTIONS} slow connections a page took {loaded:?}, without {unloaded:?}"
    );
}

/// F3: a request must arrive whole within the request time of its first
/// byte, however slowly the bytes come: then 408 and the connection closes.
#[test]
#[ignore = "end-to-end: real time, the request time of 2 s"]
fn a_request_trickling_in_is_cut_at_the_request_time() {
    let s = start(
        "trickle",
        Limits {
            request_time: Duration::from_secs(2),
            ..limits()
        },
    );
    let mut c = TcpStream::connect(("127.0.0.1", s.port)).unwrap();
    let mut writer = c.try_clone().unwrap();
    let started = Instant::now();
    let trickle = std::thread::spawn(move || {
        // A byte every 200 ms for up to 20 s: each well within the idle
        // timeout, the whole far past the request time.
        for byte in b"GET / HTTP/1.1\r\nX-Slow: "
            .iter()
            .chain([b'a'; 100].iter())
        {
            if writer.write_all(&[*byte]).is_err() {
                return;
            }
            std::thread::sleep(Duration::from_millis(200));
        }
    });
    c.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    let mut answer = Vec::new();
    let _ = c.read_to_end(&mut answer);
    let answer = String::from_utf8_lossy(&answer);
    assert!(answer.starts_with("HTTP/1.1 408 "), "{answer:?}");
    assert!(started.elapsed() < Duration::from_secs(20));
    drop(c);
    trickle.join().unwrap();
}
