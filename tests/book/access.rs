//! Who may read the book and run code: the key, the cookie, the 403 page
//! that takes the key again, `Host` and `Origin`, another user's process,
//! and `localhost` on IPv6. Each test sends requests that never reach a
//! compiler (the default tier), unless marked.

use super::*;
use spintop_server::{ServerError, fetch};
use std::io::{Read, Write};

/// Pages carry the token, for their ▶; other files do not.
#[test]
fn a_page_carries_the_token_and_other_files_do_not() {
    let s = start("page", limits());
    let (status, page) = s.get("/");
    assert_eq!(status, 200);
    assert!(page.contains(&format!(
        "window.spintopBook = {{ token: \"{}\" }}",
        s.token
    )));
    let (status, css) = s.get("/css/book.css");
    assert_eq!(status, 200);
    assert!(!css.contains(&s.token));
}

/// One raw request over bash's `/dev/tcp`, as uid 65534 (`nobody`) if
/// `other_user`, else as this user: the answer, as sent.
fn over_dev_tcp(port: u16, raw: String, other_user: bool) -> String {
    over_dev_tcp_at("127.0.0.1", port, raw, other_user)
}

/// [`over_dev_tcp`] to `host` (`127.0.0.1` or `::1`).
fn over_dev_tcp_at(host: &str, port: u16, raw: String, other_user: bool) -> String {
    use std::os::unix::process::CommandExt;
    let mut command = std::process::Command::new("bash");
    command
        .args([
            "-c",
            "exec 3<>/dev/tcp/$HOST/$PORT || exit 9; printf '%s' \"$REQUEST\" >&3; cat <&3",
        ])
        .env("HOST", host)
        .env("PORT", port.to_string())
        .env("REQUEST", raw)
        .current_dir("/");
    if other_user {
        command.uid(65534).gid(65534);
    }
    let out = command.output().unwrap();
    assert!(out.status.success(), "{out:?}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// A raw GET of `path`, and a raw run of `id` with `token` in the header.
fn raw_get_and_run(port: u16) -> (impl Fn(&str) -> String, impl Fn(&str) -> String) {
    let host = format!("Host: 127.0.0.1:{port}\r\n");
    let get = {
        let host = host.clone();
        move |path: &str| format!("GET {path} HTTP/1.1\r\n{host}Connection: close\r\n\r\n")
    };
    let run = move |token: &str| {
        let code = body("println!(\"{:?}\", std::process::Command::new(\"id\").output());");
        format!(
            "POST /evaluate.json HTTP/1.1\r\n{host}Connection: close\r\nX-Spintop-Token: {token}\r\nContent-Length: {}\r\n\r\n{}",
            code.len(),
            String::from_utf8(code).unwrap()
        )
    };
    (get, run)
}

/// F1: the port is visible to every user; the printed address is the key.
/// Another local user (`nobody`, when the test runs as root) connects, and
/// gets neither a page (from which to lift the token) nor a run; this user
/// with the printed address is let in over the same client (so the
/// refusals are the rule's, not the client's).
#[test]
fn another_local_user_cannot_read_a_page_or_run_code_without_the_printed_address() {
    let s = start("other-user", limits());
    let other_user = can_become_another_user();
    let (get, run) = raw_get_and_run(s.port);
    for (what, raw) in [
        ("the first page", get("/")),
        ("a chapter", get("/index.html")),
        ("a stylesheet", get("/css/book.css")),
        (
            "a guessed token",
            get("/?token=00000000000000000000000000000000"),
        ),
        ("a run without the token", run("")),
        (
            "a run with a guessed token",
            run("0123456789abcdef0123456789abcdef"),
        ),
    ] {
        let answer = over_dev_tcp(s.port, raw, other_user);
        assert!(answer.starts_with("HTTP/1.1 403 "), "{what}: {answer}");
        assert!(!answer.contains(&s.token), "{what}: the token leaked");
        assert!(!answer.contains("uid="), "{what}: code ran: {answer}");
    }
    // The reader with the printed address is let in.
    let answer = over_dev_tcp(s.port, get(&format!("/?token={}", s.token)), false);
    assert!(answer.starts_with("HTTP/1.1 303 "), "{answer}");
}

/// F1, the cookie: a browser sends a host's cookies to every port of it, so
/// a page of another user's server on 127.0.0.1 that the reader opens (by a
/// link, or a web page that forwards there) receives the cookie, which is
/// the token. Holding the printed address must still not let another user
/// read a page or run code; the reader, over the same client, gets both.
#[test]
fn another_local_user_holding_the_printed_address_can_neither_read_a_page_nor_run_code() {
    if !cfg!(target_os = "linux") || !can_become_another_user() {
        return;
    }
    let s = start("other-user-key", limits());
    let (get, run) = raw_get_and_run(s.port);
    let cookie = |path: &str| {
        format!(
            "GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nCookie: {}\r\nConnection: close\r\n\r\n",
            s.port,
            s.cookie()
        )
    };
    // Over IPv4 and, where the server holds it, [::1] (localhost).
    let hosts: &[&str] = match s.server.holds_localhost6() {
        true => &["127.0.0.1", "::1"],
        false => &["127.0.0.1"],
    };
    for host in hosts {
        for (what, raw) in [
            ("the printed address", get(&format!("/?token={}", s.token))),
            ("a page with the cookie", cookie("/")),
            ("a stylesheet with the cookie", cookie("/css/book.css")),
            ("a run with the token", run(&s.token)),
        ] {
            let answer = over_dev_tcp_at(host, s.port, raw, true);
            assert!(
                answer.starts_with("HTTP/1.1 403 "),
                "{host} {what}: {answer}"
            );
            assert!(answer.contains("another user"), "{host} {what}: {answer}");
            assert!(!answer.contains("Set-Cookie"), "{host} {what}: {answer}");
            assert!(!answer.contains("window.spintopBook"), "{what}: {answer}");
            assert!(
                !answer.contains("uid="),
                "{host} {what}: code ran: {answer}"
            );
        }
        // The reader, with the same request over the same client.
        let page = over_dev_tcp_at(host, s.port, cookie("/"), false);
        assert!(page.starts_with("HTTP/1.1 200 "), "{host}: {page}");
    }
}

#[test]
fn the_printed_address_sets_an_httponly_strict_cookie_named_for_the_port_and_redirects_to_the_clean_url()
 {
    let s = start("cookie", limits());
    assert_eq!(
        s.server.url(),
        format!("http://127.0.0.1:{}/?token={}", s.port, s.token)
    );
    let r = fetch(s.port, "GET", &format!("/?token={}", s.token), &[], b"").unwrap();
    assert_eq!(r.code, 303, "{r:?}");
    assert_eq!(r.header("Location"), Some("/"));
    let cookie = r.header("Set-Cookie").unwrap();
    let attributes: Vec<&str> = cookie.split(';').map(str::trim).collect();
    assert_eq!(attributes[0], s.cookie(), "{cookie}");
    assert!(attributes[0].starts_with(&format!("spintop-book-{}=", s.port)));
    assert!(attributes.contains(&"HttpOnly"), "{cookie}");
    assert!(attributes.contains(&"SameSite=Strict"), "{cookie}");
    // The rest of a query stays; the token goes.
    let r = fetch(
        s.port,
        "GET",
        &format!("/index.html?x=1&token={}&y=2", s.token),
        &[],
        b"",
    )
    .unwrap();
    assert_eq!(r.header("Location"), Some("/index.html?x=1&y=2"));
    // With the cookie, the clean address is the book.
    assert_eq!(s.get("/").0, 200);
    // A cookie with the token under another port's name is not this
    // server's key (a host's cookies are shared by all its ports).
    let elsewhere = format!("spintop-book-{}={}", s.port.wrapping_add(1), s.token);
    let (status, _) = request(s.port, "GET", "/", &[("Cookie", &elsewhere)], b"").unwrap();
    assert_eq!(status, 403);
}

/// The redirect of the printed address stays in the book: a path that a
/// browser reads as another host (`//host/`, `/\host/`) is not sent back
/// as the `Location`.
#[test]
fn the_printed_address_redirects_only_within_the_book() {
    let s = start("redirect", limits());
    for path in ["//evil.example/", "/\\evil.example/", "/\\/evil.example/"] {
        let r = fetch(
            s.port,
            "GET",
            &format!("{path}?token={}", s.token),
            &[],
            b"",
        )
        .unwrap();
        assert_eq!(r.code, 303, "{path}: {r:?}");
        let location = r.header("Location").unwrap();
        assert!(location.starts_with('/'), "{path}: {location}");
        assert!(
            !location[1..].starts_with(['/', '\\']),
            "{path}: {location} leaves the book"
        );
    }
}

#[test]
fn a_request_without_the_key_gets_a_403_page_that_says_to_open_the_printed_address() {
    let s = start("forbidden", limits());
    for path in ["/", "/index.html", "/css/book.css", "/no-such-page.html"] {
        let r = fetch(s.port, "GET", path, &[], b"").unwrap();
        assert_eq!(r.code, 403, "{path}: {r:?}");
        assert_eq!(r.header("Content-Type"), Some("text/html; charset=utf-8"));
        assert!(
            r.body.contains("Open the address printed in the terminal"),
            "{path}: {}",
            r.body
        );
        assert!(
            r.body
                .contains(&format!("http://127.0.0.1:{}/?token=", s.port))
        );
        assert!(!r.body.contains(&s.token));
    }
    // A wrong cookie is no key either.
    let wrong = format!("spintop-book-{}=0123456789abcdef0123456789abcdef", s.port);
    let (status, _) = request(s.port, "GET", "/", &[("Cookie", &wrong)], b"").unwrap();
    assert_eq!(status, 403);
}

#[test]
fn every_answer_forbids_framing_and_sniffing_and_is_not_stored() {
    let s = start("headers", limits());
    let cookie = s.cookie();
    let answers = [
        fetch(s.port, "GET", "/", &[("Cookie", &cookie)], b"").unwrap(),
        fetch(s.port, "GET", "/css/book.css", &[("Cookie", &cookie)], b"").unwrap(),
        fetch(s.port, "GET", &format!("/?token={}", s.token), &[], b"").unwrap(),
        fetch(s.port, "GET", "/", &[], b"").unwrap(),
        fetch(s.port, "GET", "/nothing", &[("Cookie", &cookie)], b"").unwrap(),
        fetch(
            s.port,
            "GET",
            "/evaluate/status",
            &[("X-Spintop-Token", &s.token)],
            b"",
        )
        .unwrap(),
    ];
    for r in &answers {
        for (name, value) in [
            ("X-Frame-Options", "DENY"),
            ("Content-Security-Policy", "frame-ancestors 'none'"),
            ("X-Content-Type-Options", "nosniff"),
            ("Referrer-Policy", "same-origin"),
            ("Cache-Control", "no-store"),
        ] {
            assert_eq!(r.header(name), Some(value), "{} {name}: {r:?}", r.code);
        }
        assert_eq!(r.header("Access-Control-Allow-Origin"), None);
    }
}

#[test]
fn a_run_without_the_token_is_refused() {
    let s = start("token", limits());
    let cookie = s.cookie();
    for headers in [
        vec![],
        vec![("X-Spintop-Token", "0123456789abcdef")],
        vec![("X-Spintop-Token", "0123456789abcdef0123456789abcdef")],
        // The cookie alone does not start a run: the page's header does.
        vec![("Cookie", cookie.as_str())],
    ] {
        let (status, text) = request(
            s.port,
            "POST",
            "/evaluate.json",
            &headers,
            &body("println!(\"x\");"),
        )
        .unwrap();
        assert_eq!(status, 403, "{text}");
        assert!(text.contains("token"), "{text}");
        let (status, _) = request(s.port, "GET", "/evaluate/status", &headers, b"").unwrap();
        assert_eq!(status, 403);
    }
}

#[test]
fn a_foreign_origin_or_host_is_refused() {
    let s = start("origin", limits());
    let (status, text) = request(
        s.port,
        "POST",
        "/evaluate.json",
        &[
            ("X-Spintop-Token", &s.token),
            ("Origin", "http://evil.example"),
        ],
        &body("println!(\"x\");"),
    )
    .unwrap();
    assert_eq!(status, 403, "{text}");
    assert!(text.contains("Origin"));
    // DNS rebinding: the page is fetched under another name.
    let host = format!("evil.example:{}", s.port);
    let cookie = s.cookie();
    for (method, path) in [("GET", "/"), ("POST", "/evaluate.json")] {
        let (status, text) = request(
            s.port,
            method,
            path,
            &[
                ("Host", &host),
                ("X-Spintop-Token", &s.token),
                ("Cookie", &cookie),
            ],
            &body("println!(\"x\");"),
        )
        .unwrap();
        assert_eq!(status, 403, "{method} {path}: {text}");
        assert!(text.contains("Host"));
    }
    // localhost:PORT and [::1]:PORT are this server too.
    for host in [format!("localhost:{}", s.port), format!("[::1]:{}", s.port)] {
        let (status, _) = request(
            s.port,
            "GET",
            "/",
            &[("Host", &host), ("Cookie", &cookie)],
            b"",
        )
        .unwrap();
        assert_eq!(status, 200, "{host}");
    }
}

#[test]
fn bad_requests_get_a_4xx_and_one_line() {
    let s = start(
        "bad",
        Limits {
            request_bytes: 1024,
            ..limits()
        },
    );
    let cookie = s.cookie();
    let key = [
        ("X-Spintop-Token", s.token.as_str()),
        ("Cookie", cookie.as_str()),
    ];
    let cases: Vec<(&str, &str, Vec<u8>, u16, &str)> = vec![
        (
            "POST",
            "/evaluate.json",
            b"{not json".to_vec(),
            400,
            "malformed",
        ),
        (
            "POST",
            "/evaluate.json",
            b"{\"edition\": \"2024\"}".to_vec(),
            400,
            "code",
        ),
        (
            "POST",
            "/evaluate.json",
            body(&"x".repeat(4096)),
            413,
            "larger than",
        ),
        ("GET", "/evaluate.json", Vec::new(), 405, "POST"),
        ("POST", "/evaluate/status", Vec::new(), 405, "GET"),
        ("PUT", "/index.html", Vec::new(), 405, "GET"),
        ("GET", "/no-such-page.html", Vec::new(), 404, "no such page"),
        ("GET", "/../Cargo.toml", Vec::new(), 404, "no such page"),
        (
            "GET",
            "/%2e%2e/%2e%2e/Cargo.toml",
            Vec::new(),
            404,
            "no such page",
        ),
    ];
    for (method, path, payload, code, says) in cases {
        let (status, text) = request(s.port, method, path, &key, &payload).unwrap();
        assert_eq!(status, code, "{method} {path}: {text}");
        assert!(text.contains(says), "{method} {path}: {text}");
        assert_eq!(text.lines().count(), 1, "one line: {text}");
    }
    // After all that the server still answers.
    assert_eq!(s.get("/").0, 200);
    // Nothing was written: the scratch folder, made fresh at start, is
    // still empty (no run got that far here).
    let written: Vec<_> = std::fs::read_dir(s.root.join("scratch"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert!(written.is_empty(), "{written:?}");
}

/// A POST of the 403 page's form, as the browser sends it from that page.
fn login(s: &Running, fields: &str, origin: &str) -> spintop_server::Response {
    fetch(
        s.port,
        "POST",
        "/login",
        &[
            ("Origin", origin),
            ("Content-Type", "application/x-www-form-urlencoded"),
        ],
        fields.as_bytes(),
    )
    .unwrap()
}

/// A browser may lose the cookie: a page of another server on 127.0.0.1
/// can overwrite it (cookies do not separate ports). The 403 page then
/// takes the key again, as the token or the whole printed address, posted
/// from the book's own origin only, and sends the browser back to the page
/// it asked for; the header still opens a page, as before.
#[test]
fn a_lost_cookie_is_taken_again_by_the_403_pages_form() {
    let s = start("login", limits());
    let own = format!("http://127.0.0.1:{}", s.port);
    // The overwritten cookie: the book's name, another value.
    let stale = format!("spintop-book-{}=0123456789abcdef0123456789abcdef", s.port);
    let r = fetch(s.port, "GET", "/ch4/top.html", &[("Cookie", &stale)], b"").unwrap();
    assert_eq!(r.code, 403);
    assert!(r.body.contains("browser lost the key"), "{}", r.body);
    assert!(
        r.body.contains("<form method=\"post\" action=\"/login\">"),
        "{}",
        r.body
    );
    assert!(
        r.body.contains("name=\"next\" value=\"/ch4/top.html\""),
        "{}",
        r.body
    );
    assert!(!r.body.contains(&s.token));
    // The token alone, and the whole address.
    let address = format!("{own}/?token={}", s.token);
    for given in [
        s.token.clone(),
        address.replace(':', "%3A").replace('/', "%2F"),
    ] {
        let r = login(&s, &format!("next=%2Fch4%2Ftop.html&token={given}"), &own);
        assert_eq!(r.code, 303, "{given}: {r:?}");
        assert_eq!(r.header("Location"), Some("/ch4/top.html"));
        assert_eq!(
            r.header("Set-Cookie")
                .map(|c| c.split(';').next().unwrap().to_string()),
            Some(s.cookie())
        );
    }
    // Not the key: the form again, with a word, and no cookie.
    let r = login(&s, "token=0123456789abcdef0123456789abcdef", &own);
    assert_eq!(r.code, 403, "{r:?}");
    assert!(r.body.contains("that is not this book's key"), "{}", r.body);
    assert_eq!(r.header("Set-Cookie"), None);
    // From another origin's page: refused before the key is looked at.
    let r = login(&s, &format!("token={}", s.token), "http://evil.example");
    assert_eq!(r.code, 403, "{r:?}");
    assert!(r.body.contains("Origin"), "{}", r.body);
    assert_eq!(r.header("Set-Cookie"), None);
    // A page asked for that is no plain path of the book is not written
    // back: the form sends the browser to the first page instead.
    for next in ["%2F%2Fevil.example%2F", "%2F%22%3E%3Cscript%3E"] {
        let r = login(&s, &format!("next={next}&token={}", s.token), &own);
        assert_eq!(r.header("Location"), Some("/"), "{next}");
        let r = fetch(
            s.port,
            "GET",
            &format!("/x?{next}"),
            &[("Cookie", &stale)],
            b"",
        )
        .unwrap();
        assert!(!r.body.contains("<script>"), "{}", r.body);
    }
    // The header still opens a page, without a cookie.
    let (status, _) = request(s.port, "GET", "/", &[("X-Spintop-Token", &s.token)], b"").unwrap();
    assert_eq!(status, 200);
}

/// One request over IPv6 loopback to `port`: the answer, as sent.
fn over_ipv6(port: u16, raw: &str) -> String {
    let mut c = std::net::TcpStream::connect(("::1", port)).unwrap();
    c.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    c.write_all(raw.as_bytes()).unwrap();
    let mut answer = String::new();
    let _ = c.read_to_string(&mut answer);
    answer
}

/// Whether this machine has IPv6 loopback (a socket can be bound on ::1).
fn has_ipv6_loopback() -> bool {
    let there = std::net::TcpListener::bind(("::1", 0)).is_ok();
    if !there {
        eprintln!("no IPv6 loopback on this machine: nobody can listen on [::1], skipped");
    }
    there
}

/// A browser resolves `localhost` to ::1 first. The server holds [::1] at
/// its port too, so that no other process can listen there and receive
/// the address with the key; `localhost:PORT` over IPv6 is this book.
#[test]
fn localhost_over_ipv6_is_this_server() {
    if !has_ipv6_loopback() {
        return;
    }
    let s = start("localhost6", limits());
    assert!(s.server.holds_localhost6());
    assert!(
        std::net::TcpListener::bind(("::1", s.port)).is_err(),
        "another listener got [::1]:{}",
        s.port
    );
    let cookie = s.cookie();
    let answer = over_ipv6(
        s.port,
        &format!(
            "GET / HTTP/1.1\r\nHost: localhost:{}\r\nCookie: {cookie}\r\nConnection: close\r\n\r\n",
            s.port
        ),
    );
    assert!(answer.starts_with("HTTP/1.1 200 "), "{answer}");
    assert!(answer.contains("window.spintopBook"), "{answer}");
    // The printed address stays 127.0.0.1.
    assert!(s.server.url().starts_with("http://127.0.0.1:"));
}

/// A listener on [::1] of another user (uid 65534, when this runs as root)
/// at the port asked for cannot receive the key: the server refuses to
/// start there and says why; with a free port asked for, it takes one
/// where [::1] is free, and holds it.
#[test]
fn a_listener_on_ipv6_of_another_user_cannot_receive_the_token() {
    use std::os::unix::process::CommandExt;
    if !has_ipv6_loopback() {
        return;
    }
    let port = {
        let probe = std::net::TcpListener::bind(("127.0.0.1", 0)).unwrap();
        probe.local_addr().unwrap().port()
    };
    // The squatter: perl (always on Debian), listening on [::1]:PORT.
    let mut squatter = std::process::Command::new("perl");
    squatter
        .args([
            "-MIO::Socket::IP",
            "-e",
            "my $s = IO::Socket::IP->new(LocalHost => '::1', LocalPort => $ARGV[0], Listen => 5, ReuseAddr => 1) or die \"$!\\n\"; print \"listening\\n\"; $| = 1; my $c = $s->accept; print while <$c>;",
            &port.to_string(),
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped());
    if can_become_another_user() {
        squatter.uid(NOBODY).gid(NOBODY);
    }
    let mut squatter = squatter.spawn().unwrap();
    let mut out = std::io::BufReader::new(squatter.stdout.take().unwrap());
    let mut first = String::new();
    out.read_line(&mut first).unwrap();
    assert_eq!(first.trim(), "listening");
    let root = scratch_root("squatted");
    let config = |port| Config {
        port,
        ..config(
            site(&root),
            root.join("scratch"),
            limits(),
            Containment::Group,
        )
    };
    match Server::bind(config(port)) {
        Err(e @ ServerError::Localhost { .. }) => {
            let said = e.to_string();
            assert!(said.contains(&format!("[::1]:{port}")), "{said}");
            assert!(said.contains("choose another --port"), "{said}");
        }
        Err(e) => panic!("refused for another reason: {e}"),
        Ok(s) => panic!("started on {} beside the squatter", s.url()),
    }
    let s = Server::bind(config(0)).unwrap();
    assert_ne!(s.port(), port);
    assert!(s.holds_localhost6());
    let _ = squatter.kill();
    let _ = squatter.wait();
    let _ = std::fs::remove_dir_all(&root);
}
