//! The answers to a reader's requests: the checks every request passes
//! (its `Host` and `Origin` are this server's, and it holds the key), the
//! book's files, and the page that takes the key again when the browser
//! lost it.

use super::{Inner, Reply, http, reason};
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

impl Inner {
    /// The answer to `request`, from the reader's process.
    pub(super) fn handle(self: &Arc<Self>, request: &http::Request) -> Reply {
        if let Some(refused) = self.foreign(request) {
            return refused;
        }
        let (path, query) = request.url.split_once('?').unwrap_or((&request.url, ""));
        let method = request.method.as_str();
        let header_token = request.header("X-Spintop-Token");
        match path {
            "/evaluate.json" | "/evaluate/status" => {
                if !header_token.is_some_and(|t| self.is_token(t)) {
                    return reason(
                        403,
                        "refused: no valid token (runs are accepted only from this book's own pages)",
                    );
                }
                self.run_request(request, path)
            }
            "/login" if method == "POST" => self.login(request),
            _ => {
                let (token, rest) = split_token(query);
                if let Some(token) = token {
                    if !self.is_token(token) {
                        return self
                            .forbidden(path, Some("the address's token is not this book's"));
                    }
                    // The printed address: keep the key in a cookie, and
                    // the address bar (and history) without it.
                    return self.keyed_redirect(path, &rest);
                }
                let keyed =
                    self.has_cookie(request) || header_token.is_some_and(|t| self.is_token(t));
                if !keyed {
                    return self.forbidden(path, None);
                }
                if method != "GET" && method != "HEAD" {
                    return reason(405, "the book is read with GET");
                }
                self.file(path)
            }
        }
    }

    /// The names of this server at its port: 127.0.0.1, and `localhost`
    /// and `[::1]`, which it holds too (see [`super::Server::bind`]).
    fn own_hosts(&self) -> [String; 3] {
        [
            format!("127.0.0.1:{}", self.port),
            format!("localhost:{}", self.port),
            format!("[::1]:{}", self.port),
        ]
    }

    /// The refusal of a request for another host (DNS rebinding) or from
    /// another origin, if it is one.
    fn foreign(&self, request: &http::Request) -> Option<Reply> {
        let host = request.header("Host").unwrap_or_default();
        let hosts = self.own_hosts();
        if !hosts.iter().any(|h| h == host) {
            return Some(reason(
                403,
                &format!("refused: Host {host:?} is not this server"),
            ));
        }
        let origin = request.header("Origin")?;
        let own = hosts.iter().any(|h| origin == format!("http://{h}"));
        (!own).then(|| reason(403, &format!("refused: Origin {origin:?} is not this book")))
    }

    /// `/evaluate.json` and `/evaluate/status`, the key checked.
    fn run_request(self: &Arc<Self>, request: &http::Request, path: &str) -> Reply {
        let method = request.method.as_str();
        if path == "/evaluate/status" {
            if method != "GET" {
                return reason(405, "use GET for /evaluate/status");
            }
            return self.status();
        }
        if method != "POST" {
            return reason(405, "use POST for /evaluate.json");
        }
        let limit = self.config.runner.limits.request_bytes;
        match &request.body {
            http::Body::Read(body) => self.evaluate(body),
            http::Body::TooLong => reason(
                413,
                &format!("the snippet is larger than {} KiB", limit / 1024),
            ),
            http::Body::Chunked => reason(411, "send the snippet with a Content-Length"),
        }
    }

    /// 303 to `path` (and the query `rest`), setting the cookie that holds
    /// the key. One leading slash: a browser reads `//host/` (or `/\host/`)
    /// as another host.
    fn keyed_redirect(&self, path: &str, rest: &str) -> Reply {
        let path = format!("/{}", path.trim_start_matches(['/', '\\']));
        let clean = if rest.is_empty() {
            path
        } else {
            format!("{path}?{rest}")
        };
        let mut reply = reason(303, "the book is at the address without its token");
        reply.headers = vec![
            ("Location", clean),
            (
                "Set-Cookie",
                format!(
                    "{}={}; HttpOnly; SameSite=Strict; Path=/",
                    self.cookie_name(),
                    self.token
                ),
            ),
        ];
        reply
    }

    /// The page for a request without the key: it says where the key is,
    /// and takes it again (a form that posts it to `/login`, then back to
    /// `path`), since a browser may lose the cookie: a page of another
    /// server on 127.0.0.1 can overwrite it, as cookies do not separate
    /// ports. `note` says why a key given was refused.
    fn forbidden(&self, path: &str, note: Option<&str>) -> Reply {
        let note = note
            .map(|n| format!("<p><strong>Refused:</strong> {n}.</p>\n"))
            .unwrap_or_default();
        let page = format!(
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>spintop book: open the printed address</title></head>\n<body><h1>Open the address printed in the terminal</h1>\n{note}<p>This book runs code on your machine, so it answers only the address that <code>spintop book</code> printed in the terminal when it started: <code>http://127.0.0.1:{port}/?token=…</code>, with its token (the key, not shown here). Copy that whole address into the browser, or start it with <code>spintop book --open</code>.</p>\n<p>If the book was open and now shows this page, the browser lost the key it kept (a page of another server on this machine can overwrite it). Paste the printed address, or its token, here:</p>\n<form method=\"post\" action=\"/login\"><input type=\"hidden\" name=\"next\" value=\"{next}\"><label for=\"key\">Address or token</label> <input id=\"key\" name=\"token\" type=\"password\" autocomplete=\"off\" autofocus size=\"60\"> <button type=\"submit\">Open the book</button></form></body></html>\n",
            port = self.port,
            next = safe_path(path),
        );
        Reply {
            code: 403,
            content_type: "text/html; charset=utf-8",
            headers: Vec::new(),
            body: page.into_bytes(),
        }
    }

    /// `POST /login` from the page of [`Inner::forbidden`]: the key again,
    /// as the token or the whole printed address; a cookie and the page
    /// asked for if it is the key, else the form again. (Another origin's
    /// form was refused before, by its `Origin`.)
    fn login(&self, request: &http::Request) -> Reply {
        let http::Body::Read(body) = &request.body else {
            return reason(413, "the form is larger than expected");
        };
        let fields = form_fields(&String::from_utf8_lossy(body));
        let field = |name: &str| {
            fields
                .iter()
                .find(|(k, _)| k == name)
                .map(|(_, v)| v.as_str())
        };
        let next = safe_path(field("next").unwrap_or("/"));
        let given = field("token").unwrap_or("").trim();
        // The whole address, or the token alone.
        let token = match given.rsplit_once("token=") {
            Some((_, t)) => t.split(['&', '#']).next().unwrap_or(""),
            None => given,
        };
        if !self.is_token(token) {
            return self.forbidden(next, Some("that is not this book's key"));
        }
        self.keyed_redirect(next, "")
    }

    /// A file of the built book; HTML pages receive the token, for their ▶.
    fn file(&self, path: &str) -> Reply {
        let Some(file) = site_file(&self.config.site, path) else {
            return reason(404, &format!("no such page: {path}"));
        };
        let Ok(mut bytes) = std::fs::read(&file) else {
            return reason(404, &format!("no such page: {path}"));
        };
        let ext = file.extension().and_then(|e| e.to_str()).unwrap_or("");
        if ext == "html" {
            let text = String::from_utf8_lossy(&bytes);
            let script = format!(
                "<script>window.spintopBook = {{ token: \"{}\" }};</script>",
                self.token
            );
            bytes = match text.find("<head>") {
                Some(i) => format!("{}{script}{}", &text[..i + 6], &text[i + 6..]),
                None => format!("{script}{text}"),
            }
            .into_bytes();
        }
        Reply {
            code: 200,
            content_type: content_type(ext),
            headers: Vec::new(),
            body: bytes,
        }
    }
}

/// `path` if it is a plain path of the book (letters, digits and
/// `/._-~%`), else `/`: it is written back into a page and a `Location`.
fn safe_path(path: &str) -> &str {
    let plain = path.starts_with('/')
        && !path.starts_with("//")
        && path
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b"/._-~%".contains(&b));
    if plain { path } else { "/" }
}

/// The fields of an `application/x-www-form-urlencoded` body, decoded
/// (`+` is a space); a malformed field is left out.
fn form_fields(body: &str) -> Vec<(String, String)> {
    body.split('&')
        .filter_map(|pair| {
            let (k, v) = pair.split_once('=').unwrap_or((pair, ""));
            let decode = |s: &str| percent_decode(&s.replace('+', " "));
            Some((decode(k)?, decode(v)?))
        })
        .collect()
}

/// A query's `token` parameter, and the query without it.
fn split_token(query: &str) -> (Option<&str>, String) {
    let mut token = None;
    let mut rest = Vec::new();
    for pair in query.split('&').filter(|p| !p.is_empty()) {
        match pair.strip_prefix("token=") {
            Some(t) if token.is_none() => token = Some(t),
            _ => rest.push(pair),
        }
    }
    (token, rest.join("&"))
}

/// The file under `site` that `path` names, if it stays inside `site`.
pub fn site_file(site: &Path, path: &str) -> Option<PathBuf> {
    let decoded = percent_decode(path)?;
    let rel = decoded.trim_start_matches('/');
    let rel = if rel.is_empty() || rel.ends_with('/') {
        format!("{rel}index.html")
    } else {
        rel.to_string()
    };
    let rel = Path::new(&rel);
    if rel.components().any(|c| !matches!(c, Component::Normal(_))) {
        return None;
    }
    let file = site.join(rel);
    file.is_file().then_some(file)
}

/// `%xx` decoding; `None` for a malformed escape or a NUL.
fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = s.get(i + 1..i + 3)?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    let text = String::from_utf8(out).ok()?;
    (!text.contains('\0')).then_some(text)
}

fn content_type(ext: &str) -> &'static str {
    match ext {
        "html" => "text/html; charset=utf-8",
        "css" => "text/css; charset=utf-8",
        "js" => "text/javascript; charset=utf-8",
        "svg" => "image/svg+xml",
        "png" => "image/png",
        "json" => "application/json",
        "woff" => "font/woff",
        "woff2" => "font/woff2",
        "ttf" => "font/ttf",
        "ico" => "image/x-icon",
        "txt" | "md" => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_outside_the_site_is_never_a_file() {
        let site = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../book/src"));
        assert!(site_file(site, "/SUMMARY.md").is_some());
        assert!(
            site_file(site, "/figures/").is_none(),
            "no index.html there"
        );
        for bad in [
            "/../Cargo.toml",
            "/figures/../../Cargo.toml",
            "/%2e%2e/Cargo.toml",
            "//etc/passwd",
            "/a%00b",
            "/%zz",
        ] {
            assert!(site_file(site, bad).is_none(), "{bad}");
        }
    }

    #[test]
    fn the_token_parameter_is_split_from_the_rest_of_the_query() {
        assert_eq!(split_token(""), (None, String::new()));
        assert_eq!(split_token("token=ab"), (Some("ab"), String::new()));
        assert_eq!(
            split_token("x=1&token=ab&y=2"),
            (Some("ab"), "x=1&y=2".to_string())
        );
        assert_eq!(split_token("tokens=ab"), (None, "tokens=ab".to_string()));
    }

    #[test]
    fn a_form_is_decoded_and_only_plain_paths_are_written_back() {
        assert_eq!(
            form_fields("next=%2Fch4.html&token=http%3A%2F%2F127.0.0.1%3A80%2F%3Ftoken%3Dab+"),
            [
                ("next".to_string(), "/ch4.html".to_string()),
                (
                    "token".to_string(),
                    "http://127.0.0.1:80/?token=ab ".to_string()
                ),
            ]
        );
        assert_eq!(
            form_fields("a=%zz&b=1"),
            [("b".to_string(), "1".to_string())]
        );
        assert_eq!(safe_path("/ch4/top.html"), "/ch4/top.html");
        for bad in [
            "//evil.example/",
            "/\\evil",
            "/\"><script>",
            "x",
            "/a b",
            "/a?b",
        ] {
            assert_eq!(safe_path(bad), "/", "{bad}");
        }
    }
}
