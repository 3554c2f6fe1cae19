//! Whose process is at the other end of a loopback connection.
//!
//! The token keeps out other origins in a browser, but a browser sends a
//! host's cookies to every port of it (cookies do not separate ports): a
//! page of another user's server on `127.0.0.1` that the reader opens, by a
//! link or a web page that forwards there, receives the reader's cookie,
//! which is the token. So on Linux the server also asks the kernel who made
//! each connection: both ends of a loopback connection are sockets of this
//! machine, listed with their owner in `/proc/net/tcp` and `/proc/net/tcp6`
//! (as `ss -tne` shows them), and a connection is taken only from a live
//! socket of the server's own user, or of root (who can read the token
//! anyway, and whose relays carry a browser's connections on WSL). Another
//! user's connection is answered 403, token or not.
//!
//! NOTE: fail closed: a peer socket not found, or already closed by its
//! process (inode 0), is refused: else a client could send its request,
//! reset its socket at once, and be gone from the table before the server
//! looks. Only where the table cannot be read at all (no `/proc`) is the
//! token the only key, as it is off Linux.

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
    let tables: Vec<String> = ["/proc/net/tcp", "/proc/net/tcp6"]
        .iter()
        .filter_map(|path| std::fs::read_to_string(path).ok())
        .collect();
    if !cfg!(target_os = "linux") || tables.is_empty() {
        return Peer::Unknown;
    }
    let me = rustix::process::geteuid().as_raw();
    let owner = tables.iter().find_map(|table| owner(table, remote, local));
    judge(owner, me)
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
}
