//! The book server's request head (`Connection::next_request`, read from a
//! real loopback socket), fed arbitrary bytes (proptest): it must return,
//! never panic, and either accept the head whole or refuse it as malformed
//! (400). Beside raw bytes, it gets heads built from the real headers with
//! hostile values.

use proptest::prelude::*;
use spintop_server::http::{Connection, ReadError};
use std::io::Write;
use std::net::{TcpListener, TcpStream};

/// The server reads `bytes` as a request from a real socket: it must come
/// back (the client has closed its side), with a request or an error, and a
/// malformed one says why in one line.
fn check_request(bytes: &[u8]) -> Result<(), TestCaseError> {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let mut client = TcpStream::connect(listener.local_addr().unwrap()).unwrap();
    let (server_side, _) = listener.accept().unwrap();
    // A write may fail once the server has refused and closed; that is fine.
    let _ = client.write_all(bytes);
    let _ = client.shutdown(std::net::Shutdown::Write);
    let mut connection = Connection::new(server_side).unwrap();
    match connection.next_request(1 << 16) {
        Ok(request) => {
            prop_assert!(!request.method.is_empty());
            prop_assert!(!request.url.is_empty());
        }
        Err(ReadError::Malformed(why)) => {
            prop_assert!(!why.contains('\n'), "two lines: {why}");
            prop_assert!(!why.trim().is_empty());
        }
        Err(_) => {}
    }
    Ok(())
}

/// A request head built from real methods and headers with hostile values:
/// lengths that do not parse or overflow, transfer codings, odd versions,
/// control bytes, a body shorter or longer than announced.
fn request_bytes() -> impl Strategy<Value = Vec<u8>> {
    let method = prop_oneof![
        Just("GET"),
        Just("POST"),
        Just("HEAD"),
        Just("PUT"),
        Just("G\u{0}T"),
        Just(""),
    ];
    let target = prop_oneof![
        Just("/".to_string()),
        Just("/evaluate.json".to_string()),
        Just("*".to_string()),
        "[ -~]{0,40}",
        "\\PC{0,20}",
    ];
    let version = prop_oneof![
        Just("HTTP/1.1"),
        Just("HTTP/1.0"),
        Just("HTTP/2.0"),
        Just("HTTP/1.x"),
        Just("")
    ];
    let header = (
        prop_oneof![
            Just("Content-Length"),
            Just("Transfer-Encoding"),
            Just("Connection"),
            Just("Host"),
            Just("Origin"),
            Just("Cookie"),
            Just("X-Spintop-Token"),
            Just("Bad Name"),
            Just(""),
        ],
        prop_oneof![
            any::<u64>().prop_map(|n| n.to_string()),
            Just("-1".to_string()),
            Just("18446744073709551616".to_string()),
            Just("chunked".to_string()),
            Just("keep-alive".to_string()),
            Just("close".to_string()),
            "[ -~]{0,30}",
            "\\PC{0,20}",
        ],
    );
    (
        method,
        target,
        version,
        prop::collection::vec(header, 0..8),
        prop::collection::vec(any::<u8>(), 0..64),
        any::<bool>(),
    )
        .prop_map(|(method, target, version, headers, body, crlf)| {
            let eol = if crlf { "\r\n" } else { "\n" };
            let mut head = format!("{method} {target} {version}{eol}");
            for (name, value) in headers {
                head.push_str(&format!("{name}: {value}{eol}"));
            }
            head.push_str(eol);
            let mut bytes = head.into_bytes();
            bytes.extend(body);
            bytes
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn request_head_parser_refuses_any_bytes_or_accepts_them(
        bytes in prop::collection::vec(any::<u8>(), 0..600)
    ) {
        check_request(&bytes)?;
    }

    #[test]
    fn request_head_parser_refuses_hostile_heads_in_one_line(bytes in request_bytes()) {
        check_request(&bytes)?;
    }
}

#[test]
fn a_request_head_longer_than_the_cap_is_malformed_not_read_on() {
    let mut bytes = b"GET / HTTP/1.1\r\nX: ".to_vec();
    bytes.extend(std::iter::repeat_n(b'a', 40 * 1024));
    bytes.extend(b"\r\n\r\n");
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let mut client = TcpStream::connect(listener.local_addr().unwrap()).unwrap();
    let (server_side, _) = listener.accept().unwrap();
    let writer = std::thread::spawn(move || {
        let _ = client.write_all(&bytes);
    });
    let mut connection = Connection::new(server_side).unwrap();
    match connection.next_request(1 << 16) {
        Err(ReadError::Malformed(why)) => assert!(why.contains("longer than"), "{why}"),
        other => panic!("expected a malformed head, got {other:?}"),
    }
    drop(connection);
    writer.join().unwrap();
}
