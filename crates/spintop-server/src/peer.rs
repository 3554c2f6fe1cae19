//! Whose process is at the other end of a loopback connection.
//!
//! The token keeps out other origins in a browser, but a browser sends a
//! host's cookies to every port of it (cookies do not separate ports): a
//! page of another user's server on `127.0.0.1` that the reader opens, by a
//! link or a web page that forwards there, receives the reader's cookie,
//! which is the token. So on Linux the server also asks the kernel who made
//! each connection: both ends of a loopback connection are sockets of this
//! machine, and the kernel's socket diagnostics name the owner of the peer's
//! socket in one lookup (as `ss -tne` asks; the tables `/proc/net/tcp` and
//! `/proc/net/tcp6` say the same, slowly, and are read only where the
//! diagnostics cannot answer). A connection is taken only from a live
//! socket of the server's own user, or of root (who can read the token
//! anyway, and whose relays carry a browser's connections on WSL). Another
//! user's connection is answered 403, token or not.
//!
//! NOTE: fail closed: a peer socket not found, or already closed by its
//! process (inode 0), is refused: else a client could send its request,
//! reset its socket at once, and be gone from the table before the server
//! looks. Only where neither the diagnostics nor the tables can be read
//! (no `/proc`) is the token the only key, as it is off Linux.

use std::net::{IpAddr, Ipv4Addr, Ipv6Addr, SocketAddr, TcpStream};

/// Who made a connection, as far as the kernel says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Peer {
    /// A live socket of this user or of root.
    Trusted,
    /// A live socket of another user.
    OtherUser(u32),
    /// The peer's socket is closed or not listed: nobody can be asked.
    Gone,
    /// The socket tables cannot be read (not Linux, no `/proc`).
    Unknown,
}

/// Who is at the other end of `stream`, a connection accepted on loopback.
pub fn peer(stream: &TcpStream) -> Peer {
    let (Ok(remote), Ok(local)) = (stream.peer_addr(), stream.local_addr()) else {
        return Peer::Gone;
    };
    if !cfg!(target_os = "linux") {
        return Peer::Unknown;
    }
    let me = rustix::process::geteuid().as_raw();
    // The kernel's socket diagnostics first: one socket looked up by its
    // addresses, in microseconds. The tables below are read whole, and the
    // kernel walks every hash bucket to write them: 20-odd ms per
    // connection on an idle machine, ten times that on a busy one, paid on
    // the accept loop (64 slow connections held a page load up for 10 s).
    if let Some(owner) = diag::owner(remote, local) {
        return judge(owner, me);
    }
    let tables = tables();
    if tables.is_empty() {
        return Peer::Unknown;
    }
    let owner = tables.iter().find_map(|table| owner(table, remote, local));
    judge(owner, me)
}

/// The kernel's TCP socket tables, IPv4 and IPv6 (those it can read).
fn tables() -> Vec<String> {
    ["/proc/net/tcp", "/proc/net/tcp6"]
        .iter()
        .filter_map(|path| std::fs::read_to_string(path).ok())
        .collect()
}

/// The owner of a loopback socket from the kernel's socket diagnostics
/// (`NETLINK_SOCK_DIAG`, as `ss` asks; `man 7 sock_diag`): one exact lookup
/// by the socket's four addresses instead of a walk over the tables.
#[cfg(target_os = "linux")]
mod diag {
    use rustix::net::{
        AddressFamily, RecvFlags, SendFlags, SocketType, netlink, recv, send, socket,
    };
    use std::net::{IpAddr, SocketAddr};

    /// `SOCK_DIAG_BY_FAMILY`, `NLM_F_REQUEST`, `NLMSG_ERROR` (linux/sock_diag.h, linux/netlink.h).
    const BY_FAMILY: u16 = 20;
    const REQUEST: u16 = 1;
    const ERROR: u16 = 2;
    /// `INET_DIAG_NOCOOKIE`: look up by addresses alone.
    const NO_COOKIE: u32 = u32::MAX;

    /// What the kernel says of the socket at `remote` talking to `local`:
    /// `Some(Some((uid, inode)))` found, `Some(None)` not there (closed),
    /// `None` when the diagnostics cannot answer (then read the tables).
    pub fn owner(remote: SocketAddr, local: SocketAddr) -> Option<Option<(u32, u64)>> {
        let fd = socket(
            AddressFamily::NETLINK,
            SocketType::RAW,
            Some(netlink::SOCK_DIAG),
        )
        .ok()?;
        let ask = |from: SocketAddr, to: SocketAddr| -> Option<Option<(u32, u64)>> {
            // An IPv4 address is listed under IPv4, or, for a client's IPv6
            // socket, as an IPv4-mapped IPv6 address.
            let forms: Vec<(SocketAddr, SocketAddr)> = match (from.ip(), to.ip()) {
                (IpAddr::V4(a), IpAddr::V4(b)) => vec![
                    (from, to),
                    (
                        SocketAddr::new(IpAddr::V6(a.to_ipv6_mapped()), from.port()),
                        SocketAddr::new(IpAddr::V6(b.to_ipv6_mapped()), to.port()),
                    ),
                ],
                _ => vec![(from, to)],
            };
            for (a, b) in forms {
                match lookup(&fd, a, b)? {
                    Some(found) => return Some(Some(found)),
                    None => continue,
                }
            }
            Some(None)
        };
        match ask(remote, local)? {
            Some(found) => Some(Some(found)),
            // Not listed: closed, or diagnostics that list nothing (no
            // `inet_diag` in this kernel). The server's own end of the
            // connection is listed while it is open: if it is not found
            // either, the diagnostics cannot be trusted to answer.
            None => ask(local, remote)?.map(|_| None),
        }
    }

    /// One `inet_diag_req_v2` for the TCP socket whose source is `from` and
    /// destination `to`: `Some(Some((uid, inode)))`, `Some(None)` for
    /// ENOENT, `None` for any other failure.
    fn lookup(
        fd: &rustix::fd::OwnedFd,
        from: SocketAddr,
        to: SocketAddr,
    ) -> Option<Option<(u32, u64)>> {
        let family = match from.ip() {
            IpAddr::V4(_) => AddressFamily::INET,
            IpAddr::V6(_) => AddressFamily::INET6,
        };
        let address = |a: SocketAddr| -> [u8; 16] {
            let mut bytes = [0u8; 16];
            match a.ip() {
                IpAddr::V4(v4) => bytes[..4].copy_from_slice(&v4.octets()),
                IpAddr::V6(v6) => bytes.copy_from_slice(&v6.octets()),
            }
            bytes
        };
        // nlmsghdr (16 bytes), then inet_diag_req_v2 (56): family,
        // protocol, extensions, padding, states; the socket id: ports and
        // addresses in network order, interface, cookie.
        let mut message = Vec::with_capacity(72);
        message.extend_from_slice(&72u32.to_ne_bytes());
        message.extend_from_slice(&BY_FAMILY.to_ne_bytes());
        message.extend_from_slice(&REQUEST.to_ne_bytes());
        message.extend_from_slice(&1u32.to_ne_bytes());
        message.extend_from_slice(&0u32.to_ne_bytes());
        message.push(u8::try_from(family.as_raw()).ok()?);
        message.push(6); // IPPROTO_TCP
        message.extend_from_slice(&[0, 0]);
        message.extend_from_slice(&u32::MAX.to_ne_bytes()); // every state
        message.extend_from_slice(&from.port().to_be_bytes());
        message.extend_from_slice(&to.port().to_be_bytes());
        message.extend_from_slice(&address(from));
        message.extend_from_slice(&address(to));
        message.extend_from_slice(&0u32.to_ne_bytes());
        message.extend_from_slice(&NO_COOKIE.to_ne_bytes());
        message.extend_from_slice(&NO_COOKIE.to_ne_bytes());
        if send(fd, &message, SendFlags::empty()).ok()? != message.len() {
            return None;
        }
        let mut reply = [0u8; 512];
        let (n, _) = recv(fd, &mut reply[..], RecvFlags::empty()).ok()?;
        let reply = reply.get(..n)?;
        let u16_at = |i: usize| Some(u16::from_ne_bytes(reply.get(i..i + 2)?.try_into().ok()?));
        let u32_at = |i: usize| Some(u32::from_ne_bytes(reply.get(i..i + 4)?.try_into().ok()?));
        match u16_at(4)? {
            ERROR => {
                let errno = i32::from_ne_bytes(reply.get(16..20)?.try_into().ok()?);
                (errno == -2).then_some(None) // ENOENT: no such socket
            }
            BY_FAMILY => {
                // inet_diag_msg after the header: 4 bytes, the id (48),
                // expires, rqueue, wqueue, then uid and inode.
                let (uid, inode) = (u32_at(16 + 64)?, u32_at(16 + 68)?);
                Some(Some((uid, u64::from(inode))))
            }
            _ => None,
        }
    }
}

#[cfg(not(target_os = "linux"))]
mod diag {
    pub fn owner(_: std::net::SocketAddr, _: std::net::SocketAddr) -> Option<Option<(u32, u64)>> {
        None
    }
}

/// The verdict on the owner of the peer's socket (`uid`, `inode`).
fn judge(owner: Option<(u32, u64)>, me: u32) -> Peer {
    match owner {
        Some((_, 0)) | None => Peer::Gone,
        Some((uid, _)) if uid == me || uid == 0 => Peer::Trusted,
        Some((uid, _)) => Peer::OtherUser(uid),
    }
}

/// The owner (`uid`, `inode`) of the socket listed in `table` (the text of
/// `/proc/net/tcp` or `tcp6`) whose own address is `remote` and whose
/// peer is `local`: the other end of our connection.
fn owner(table: &str, remote: SocketAddr, local: SocketAddr) -> Option<(u32, u64)> {
    table.lines().skip(1).find_map(|line| {
        // sl local rem st tx:rx tr:when retrnsmt uid timeout inode …
        let fields: Vec<&str> = line.split_whitespace().collect();
        let (own, peer) = (address(fields.get(1)?)?, address(fields.get(2)?)?);
        if !same(own, remote) || !same(peer, local) {
            return None;
        }
        Some((fields.get(7)?.parse().ok()?, fields.get(9)?.parse().ok()?))
    })
}

/// Whether two addresses are one, an IPv4-mapped IPv6 address being its
/// IPv4 address.
fn same(a: SocketAddr, b: SocketAddr) -> bool {
    let plain = |ip: IpAddr| match ip {
        IpAddr::V6(v6) => v6.to_ipv4_mapped().map_or(ip, IpAddr::V4),
        v4 => v4,
    };
    a.port() == b.port() && plain(a.ip()) == plain(b.ip())
}

/// An address of the socket tables: `0100007F:1F90` (IPv4) or 32 hex
/// digits and a port (IPv6); each 32-bit word is printed as the host reads
/// the network-order bytes, so `to_ne_bytes` gives them back.
fn address(field: &str) -> Option<SocketAddr> {
    let (ip, port) = field.split_once(':')?;
    let port = u16::from_str_radix(port, 16).ok()?;
    let word = |i: usize| -> Option<[u8; 4]> {
        let hex = ip.get(8 * i..8 * i + 8)?;
        Some(u32::from_str_radix(hex, 16).ok()?.to_ne_bytes())
    };
    let ip = match ip.len() {
        8 => IpAddr::V4(Ipv4Addr::from(word(0)?)),
        32 => {
            let mut bytes = [0u8; 16];
            for i in 0..4 {
                bytes[4 * i..4 * i + 4].copy_from_slice(&word(i)?);
            }
            IpAddr::V6(Ipv6Addr::from(bytes))
        }
        _ => return None,
    };
    Some(SocketAddr::new(ip, port))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A client socket (port 0xA1B2, uid 65534) and the server's side of
    /// the connection (port 0x1F90, uid 1000), as Linux lists them on a
    /// little-endian machine; an IPv6 client on `::ffff:127.0.0.1`; and an
    /// orphan (inode 0).
    const TABLE: &str = "  sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid  timeout inode
   0: 0100007F:A1B2 0100007F:1F90 01 00000000:00000000 00:00000000 00000000 65534        0 4242 1 0000000000000000 20 4 30 10 -1
   1: 0100007F:1F90 0100007F:A1B2 01 00000000:00000000 00:00000000 00000000  1000        0 4243 1 0000000000000000 20 4 30 10 -1
   2: 0100007F:C3D4 0100007F:1F90 04 00000000:00000000 00:00000000 00000000  1000        0 0 1 0000000000000000 20 4 30 10 -1
";
    const TABLE6: &str = "  sl  local_address                         remote_address                        st tx_queue rx_queue tr tm->when retrnsmt   uid  timeout inode
   0: 0000000000000000FFFF00000100007F:B00B 0000000000000000FFFF00000100007F:1F90 01 00000000:00000000 00:00000000 00000000  1000        0 777 1 0000000000000000 20 4 30 10 -1
";

    fn at(port: u16) -> SocketAddr {
        SocketAddr::from(([127, 0, 0, 1], port))
    }

    #[test]
    fn the_peer_socket_and_its_owner_are_found_in_the_tables() {
        if cfg!(target_endian = "big") {
            return;
        }
        let server = at(0x1F90);
        assert_eq!(owner(TABLE, at(0xA1B2), server), Some((65534, 4242)));
        assert_eq!(owner(TABLE, at(0xC3D4), server), Some((1000, 0)));
        assert_eq!(owner(TABLE, at(0x1234), server), None);
        assert_eq!(owner(TABLE6, at(0xB00B), server), Some((1000, 777)));
        // The server's own side is not the peer.
        assert_eq!(owner(TABLE, server, at(0xA1B2)), Some((1000, 4243)));
    }

    #[test]
    fn only_a_live_socket_of_this_user_or_root_is_trusted() {
        assert_eq!(judge(Some((1000, 5)), 1000), Peer::Trusted);
        assert_eq!(judge(Some((0, 5)), 1000), Peer::Trusted);
        assert_eq!(judge(Some((65534, 5)), 1000), Peer::OtherUser(65534));
        assert_eq!(judge(Some((1000, 0)), 1000), Peer::Gone);
        assert_eq!(judge(Some((0, 0)), 0), Peer::Gone);
        assert_eq!(judge(None, 1000), Peer::Gone);
    }

    #[test]
    fn a_real_loopback_connection_is_this_users() {
        let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        let client = TcpStream::connect(listener.local_addr().unwrap()).unwrap();
        let (accepted, _) = listener.accept().unwrap();
        let expected = if cfg!(target_os = "linux") {
            Peer::Trusted
        } else {
            Peer::Unknown
        };
        assert_eq!(peer(&accepted), expected);
        drop(client);
    }

    /// The kernel's diagnostics and the tables are two ways to one answer:
    /// for a live connection both name the same owner and inode (the
    /// client's socket), and for the server's own end as well.
    #[cfg(target_os = "linux")]
    #[test]
    fn the_socket_diagnostics_agree_with_the_tables() {
        let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        let client = TcpStream::connect(listener.local_addr().unwrap()).unwrap();
        let (accepted, _) = listener.accept().unwrap();
        let (remote, local) = (
            accepted.peer_addr().unwrap(),
            accepted.local_addr().unwrap(),
        );
        let tables = tables();
        let from_tables = |a, b| tables.iter().find_map(|t| owner(t, a, b));
        let Some(client_side) = diag::owner(remote, local) else {
            eprintln!("no socket diagnostics in this kernel: the tables alone answer");
            return;
        };
        assert_eq!(client_side, from_tables(remote, local));
        assert!(client_side.is_some_and(|(_, inode)| inode != 0));
        assert_eq!(
            diag::owner(local, remote).unwrap(),
            from_tables(local, remote)
        );
        // A port nobody uses is not found: closed, never trusted.
        let unused = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        let nobody = unused.local_addr().unwrap();
        drop(unused);
        assert_eq!(diag::owner(nobody, local), Some(None));
        drop(client);
    }
}
