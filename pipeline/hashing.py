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


CACHE_MARK = "<cache>"


def _cache_prefixes() -> list:
    """How a path into the run cache can be spelt in a payload: absolute (as given and resolved)
    and, for a cache inside the repository, repository-relative (what configs carry)."""
    from pipeline import paths
    spelt = {str(paths.CACHE), str(paths.CACHE.resolve()), paths.rel(paths.CACHE)}
    return sorted((p.rstrip("/") + "/" for p in spelt if p not in ("", ".")), key=len, reverse=True)


def location_free_json(value) -> str:
    """`value` as canonical JSON with every path into the cache written from the cache's root
    (`<cache>/artifacts/...`): a payload that names an input artifact hashes the same wherever
    the cache lies. Artifacts are named by their keys, so the rest of such a path is the same."""
    text = json.dumps(value, sort_keys=True, separators=(",", ":"))
    for prefix in _cache_prefixes():
        text = text.replace(json.dumps(prefix)[1:-1], CACHE_MARK + "/")
    return text


@lru_cache(maxsize=None)
def _content_hash_cached(path: str, mtime_ns: int, size: int) -> str:
    with open(path) as f:
        doc = json.load(f)
    return sha256_bytes(location_free_json({"schema": doc.get("schema"), "payload": doc.get("payload")}).encode())


def content_hash(path) -> str:
    """Hash of an artifact's schema and payload, without its provenance: what a downstream run
    actually consumes. The provenance names the commit, so keying on the whole file would
    rerun every downstream stage after every commit. Paths into the cache count from the
    cache's root (location_free_json), so the keys do not depend on where the cache lies."""
    p = Path(path)
    st = p.stat()
    return _content_hash_cached(str(p), st.st_mtime_ns, st.st_size)
