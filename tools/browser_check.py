"""Open a Meshcat HTML replay in headless Chromium and check from screenshots that it draws.

    python3 tools/browser_check.py replay.html --robot /drake/robot0/car --out shot.png

Chromium is driven over its DevTools protocol (a small stdlib websocket client,
no extra packages): load the page, wait until Meshcat has built its meshes and
the recording, stop the animation at its end (the robot at its goal), then take
screenshots, hiding one group at a time — the robot, its target (e.g. the
goal region it should reach), then everything under ``/drake``. Pixels that
change when a group is hidden are that group's. A plain ``chromium --screenshot`` fires before the meshes
load, hence the protocol.
"""

from __future__ import annotations

import argparse
import base64
import io
import json
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

import numpy as np

CHROMIUM = "/usr/bin/chromium"
FLAGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--enable-unsafe-swiftshader",  # software WebGL without a GPU
    "--hide-scrollbars", "--mute-audio",
]
MESH_COUNT_JS = "(() => { if (typeof viewer === 'undefined') return -1; let n = 0; viewer.scene.traverse(o => { if (o.isMesh || o.isPoints || o.isLine) n++; }); return n; })()"
ANIMATION_JS = "(typeof viewer === 'undefined') ? -1 : viewer.animator.actions.length"
STOP_AT_END_JS = "viewer.animator.pause(); viewer.animator.seek(1e9); true"


class _WebSocket:
    """Just enough RFC 6455 for the DevTools protocol: masked text frames out, frames in."""

    def __init__(self, url: str, timeout: float):
        assert url.startswith("ws://")
        hostport, _, path = url[5:].partition("/")
        host, _, port = hostport.partition(":")
        self.sock = socket.create_connection((host, int(port)), timeout=timeout)
        key = base64.b64encode(os.urandom(16)).decode()
        self.sock.sendall(
            f"GET /{path} HTTP/1.1\r\nHost: {hostport}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
            f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n".encode()
        )
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.sock.recv(4096)
            if not chunk:
                raise ConnectionError("websocket handshake: connection closed")
            head += chunk
        if b" 101 " not in head.split(b"\r\n", 1)[0]:
            raise ConnectionError(f"websocket handshake failed: {head.splitlines()[0]!r}")
        self.buffer = head.split(b"\r\n\r\n", 1)[1]

    def send(self, text: str) -> None:
        payload = text.encode()
        n = len(payload)
        header = bytes([0x81])
        if n < 126:
            header += bytes([0x80 | n])
        elif n < 1 << 16:
            header += bytes([0x80 | 126]) + struct.pack(">H", n)
        else:
            header += bytes([0x80 | 127]) + struct.pack(">Q", n)
        mask = os.urandom(4)
        masked = bytes(b ^ mask[i % 4] for i, b in enumerate(payload))
        self.sock.sendall(header + mask + masked)

    def _read(self, n: int) -> bytes:
        while len(self.buffer) < n:
            chunk = self.sock.recv(1 << 20)
            if not chunk:
                raise ConnectionError("websocket closed")
            self.buffer += chunk
        out, self.buffer = self.buffer[:n], self.buffer[n:]
        return out

    def recv(self) -> str:
        parts = []
        while True:
            b0, b1 = self._read(2)
            n = b1 & 0x7F
            if n == 126:
                n = struct.unpack(">H", self._read(2))[0]
            elif n == 127:
                n = struct.unpack(">Q", self._read(8))[0]
            mask = self._read(4) if b1 & 0x80 else None
            data = self._read(n)
            if mask:
                data = bytes(b ^ mask[i % 4] for i, b in enumerate(data))
            opcode = b0 & 0x0F
            if opcode == 0x8:
                raise ConnectionError("websocket closed by the browser")
            if opcode in (0x9, 0xA):  # ping/pong: ignore
                continue
            parts.append(data)
            if b0 & 0x80:
                return b"".join(parts).decode()

    def close(self) -> None:
        self.sock.close()


class Chromium:
    """A headless Chromium with one page, driven over the DevTools protocol."""

    def __init__(self, width: int = 1024, height: int = 768, timeout: float = 30.0):
        if not Path(CHROMIUM).exists():
            raise FileNotFoundError(f"{CHROMIUM} not found (apt-get install chromium)")
        self.timeout = timeout
        self.profile = tempfile.mkdtemp(prefix="lazyground-chromium-")
        self.proc = subprocess.Popen(
            [CHROMIUM, *FLAGS, f"--user-data-dir={self.profile}", "--remote-debugging-port=0",
             f"--window-size={width},{height}", "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        )
        try:
            port = self._port()
            pages = [t for t in self._json(port, "list") if t.get("type") == "page"]
            self.ws = _WebSocket(pages[0]["webSocketDebuggerUrl"], timeout)
        except BaseException:
            self.close()
            raise
        self._id = 0
        self.events: list[dict] = []  # DevTools events seen while waiting for replies

    def _port(self) -> int:
        active = Path(self.profile) / "DevToolsActivePort"
        deadline = time.monotonic() + self.timeout
        while time.monotonic() < deadline:
            if active.exists() and active.read_text().strip():
                return int(active.read_text().split()[0])
            if self.proc.poll() is not None:
                raise RuntimeError(f"chromium exited with code {self.proc.returncode}")
            time.sleep(0.05)
        raise TimeoutError("chromium did not open its DevTools port")

    def _json(self, port: int, what: str):
        deadline = time.monotonic() + self.timeout
        while True:
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/{what}", timeout=5) as r:
                    out = json.load(r)
                if out:
                    return out
            except OSError:
                if time.monotonic() > deadline:
                    raise
            time.sleep(0.1)

    def call(self, method: str, **params) -> dict:
        self._id += 1
        self.ws.send(json.dumps({"id": self._id, "method": method, "params": params}))
        while True:
            msg = json.loads(self.ws.recv())
            if "method" in msg:
                self.events.append(msg)
            elif msg.get("id") == self._id:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error']}")
                return msg.get("result", {})

    def evaluate(self, expression: str):
        res = self.call("Runtime.evaluate", expression=expression, returnByValue=True)
        if "exceptionDetails" in res:
            raise RuntimeError(f"javascript error: {res['exceptionDetails'].get('text')}")
        return res["result"].get("value")

    def screenshot(self) -> np.ndarray:
        from PIL import Image

        data = base64.b64decode(self.call("Page.captureScreenshot", format="png")["data"])
        return np.asarray(Image.open(io.BytesIO(data)).convert("RGB"))

    def close(self) -> None:
        ws = getattr(self, "ws", None)
        if ws is not None:
            ws.close()
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        shutil.rmtree(self.profile, ignore_errors=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _changed(a: np.ndarray, b: np.ndarray, threshold: int = 24) -> np.ndarray:
    return np.abs(a.astype(int) - b.astype(int)).max(axis=2) > threshold


def _hide(chrome: Chromium, path: str) -> None:
    chrome.evaluate(f"viewer.handle_command({{type: 'set_property', path: {json.dumps(path)}, property: 'visible', value: false}}); true")


def _box(mask: np.ndarray):
    ys, xs = np.nonzero(mask)
    return (int(xs.min()), int(ys.min()), int(xs.max()), int(ys.max())) if len(xs) else None


def _shot(chrome: Chromium) -> np.ndarray:
    chrome.evaluate("viewer.set_dirty(); true")
    time.sleep(0.4)  # a few animation frames to render
    return chrome.screenshot()


def load_replay(chrome: Chromium, html: str | Path, timeout: float) -> tuple[int, int]:
    """Open ``html``, wait until its scene stops growing and its recording is in, stop at the end.

    Returns:
        (objects drawn, animation tracks).

    Raises:
        TimeoutError: the replay did not load within ``timeout`` seconds.
    """
    chrome.call("Page.enable")
    chrome.call("Network.enable")
    chrome.call("Page.navigate", url=Path(html).resolve().as_uri())
    deadline = time.monotonic() + timeout
    last, stable_since = -2, time.monotonic()
    while True:  # wait until the scene stops growing and the recording is in
        n = chrome.evaluate(MESH_COUNT_JS)
        tracks = chrome.evaluate(ANIMATION_JS)
        now = time.monotonic()
        if n != last:
            last, stable_since = n, now
        if n > 0 and tracks and tracks > 0 and now - stable_since > 1.0:
            break
        if now > deadline:
            raise TimeoutError(f"the replay did not load within {timeout:g} s (objects {n}, tracks {tracks})")
        time.sleep(0.2)
    chrome.evaluate(STOP_AT_END_JS)
    return last, tracks


def shot(chrome: Chromium) -> np.ndarray:
    """A screenshot after a few frames are rendered."""
    return _shot(chrome)


def changed_pixels(a: np.ndarray, b: np.ndarray) -> int:
    """How many pixels differ between two screenshots."""
    return int(_changed(a, b).sum())


def check_replay(html: str | Path, robot: list[str], target: list[str] = (), out: str | Path | None = None,
                 timeout: float = 40.0) -> dict:
    """Load a Meshcat replay, wait for it, stop it at its end and measure what it draws.

    Args:
        html: the HTML file.
        robot: Meshcat paths of the robot (hidden for the second screenshot).
        target: Meshcat paths of what the robot should reach (hidden next).
        out: where to save the first screenshot (PNG), if given.

    Returns:
        objects (meshes, lines and points in the scene), animation_tracks,
        robot_pixels, target_pixels, scene_pixels (everything under /drake
        but the robot), robot_box and target_box ((x0, y0, x1, y1) of those
        pixels), image_size, load_s, and external_requests (URLs the page
        fetched that are not file:, data: or blob:; empty for an offline page).
    """
    t0 = time.monotonic()
    with Chromium(timeout=timeout) as chrome:
        last, tracks = load_replay(chrome, html, timeout)
        load_s = time.monotonic() - t0
        shots = [_shot(chrome)]
        for group in (robot, target, ["/drake"]):
            for path in group:
                _hide(chrome, path)
            shots.append(_shot(chrome))
    full, no_robot, no_target, empty = shots
    requests = [e["params"]["request"]["url"] for e in chrome.events if e["method"] == "Network.requestWillBeSent"]
    if out is not None:
        from PIL import Image

        Image.fromarray(full).save(out)
    robot_mask, target_mask = _changed(full, no_robot), _changed(no_robot, no_target)
    return {
        "objects": last,
        "animation_tracks": tracks,
        "robot_pixels": int(robot_mask.sum()),
        "target_pixels": int(target_mask.sum()),
        "scene_pixels": int(_changed(no_target, empty).sum()),
        "robot_box": _box(robot_mask),
        "target_box": _box(target_mask),
        "image_size": full.shape[:2],
        "load_s": round(load_s, 2),
        "requests": len(requests),
        "external_requests": [u for u in requests if not u.startswith(("file:", "data:", "blob:"))],
    }


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("html")
    p.add_argument("--robot", action="append", default=[], help="Meshcat path of the robot (repeatable)")
    p.add_argument("--target", action="append", default=[], help="Meshcat path of what the robot reaches (repeatable)")
    p.add_argument("--out", help="save the screenshot here")
    args = p.parse_args(argv)
    print(json.dumps(check_replay(args.html, args.robot, args.target, args.out)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
