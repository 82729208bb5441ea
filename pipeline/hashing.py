"""Content hashes for the cache keys."""
import hashlib
import json
from functools import lru_cache
from pathlib import Path


def sha256_bytes(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def sha256_file(path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


@lru_cache(maxsize=None)
def sha256_file_cached(path: str, mtime_ns: int, size: int) -> str:
    return sha256_file(path)


def file_hash(path) -> str:
    """sha256 of a file, memoised on (path, mtime, size) within one pipeline invocation."""
    p = Path(path)
    st = p.stat()
    return sha256_file_cached(str(p), st.st_mtime_ns, st.st_size)


def sha256_json(value) -> str:
    return sha256_bytes(json.dumps(value, sort_keys=True, separators=(",", ":")).encode())


@lru_cache(maxsize=None)
def _content_hash_cached(path: str, mtime_ns: int, size: int) -> str:
    with open(path) as f:
        doc = json.load(f)
    return sha256_json({"schema": doc.get("schema"), "payload": doc.get("payload")})


def content_hash(path) -> str:
    """Hash of an artifact's schema and payload, without its provenance: what a downstream run
    actually consumes. The provenance names the commit, so keying on the whole file would
    rerun every downstream stage after every commit."""
    p = Path(path)
    st = p.stat()
    return _content_hash_cached(str(p), st.st_mtime_ns, st.st_size)
