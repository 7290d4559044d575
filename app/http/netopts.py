"""TCP_NODELAY on the server's listening sockets, so that ``uvicorn --workers N`` answers without Nagle's delay.

With ``--workers`` uvicorn binds the socket itself with ``socket.socket(family)``: its ``proto`` is 0, so asyncio's
transport does not recognise it as TCP and never sets TCP_NODELAY on the accepted connections (uvicorn issue
#3149). A small response then waits for the client's delayed ACK: about 40 ms a request on a kept-alive connection.
Linux copies TCP_NODELAY from a listening socket to every connection it accepts, so setting it once on each
listening TCP socket of the process fixes every worker whatever the server: the app does it at start-up.
"""

from __future__ import annotations

import os
import socket


def _fds() -> list[int]:
    for where in ("/proc/self/fd", "/dev/fd"):
        try:
            return [int(name) for name in os.listdir(where)]
        except (OSError, ValueError):
            continue
    return []


def _unconnected_tcp(sock: socket.socket) -> bool:
    """A bound TCP socket that is not a connection: a listening socket, or one about to listen (uvicorn's workers
    run the app's start-up before they call listen on the socket the parent bound)."""
    if sock.family not in (socket.AF_INET, socket.AF_INET6) or sock.type != socket.SOCK_STREAM:
        return False
    if sock.getsockname()[1] == 0:
        return False
    try:
        sock.getpeername()
    except OSError:
        return True
    return False


def set_nodelay_on_listening_sockets() -> int:
    """Set TCP_NODELAY on every listening (or bound, not yet listening) TCP socket of this process; the number of
    sockets set."""
    count = 0
    for fd in _fds():
        try:
            dup = os.dup(fd)
        except OSError:
            continue
        try:
            sock = socket.socket(fileno=dup)
        except OSError:  # not a socket (a file, a pipe): close the duplicate and go on
            os.close(dup)
            continue
        try:
            if _unconnected_tcp(sock):
                sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
                count += 1
        except OSError:
            pass
        finally:
            sock.close()  # the duplicate only; the server's descriptor stays open
    return count
