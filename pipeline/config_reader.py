"""Strict reading of a stage's JSON config, in the spirit of io::JsonReader in the C++ tools:
read every key you understand, then reject_unknown(); every error names the source, the JSON
pointer and what was expected, and is a ConfigError (the stage's config is at fault)."""
import math


class ConfigError(ValueError):
    """A malformed stage config: names the JSON pointer and what was expected."""


class ConfigReader:
    """Strict reading of a dict config, in the spirit of io::JsonReader: read every key you
    understand, then call reject_unknown(); errors name the JSON pointer."""

    def __init__(self, value, pointer="", source="config"):
        self.value = value
        self.pointer = pointer
        self.source = source
        self._read = set()

    def fail(self, expected, key=None):
        where = self.pointer + (f"/{key}" if key is not None else "")
        raise ConfigError(f"{self.source}: {where or '/'}: expected {expected}")

    def require_object(self):
        if not isinstance(self.value, dict):
            self.fail("an object")
        return self

    def has(self, key):
        return isinstance(self.value, dict) and key in self.value

    def raw(self, key, default=None, required=False):
        self.require_object()
        self._read.add(key)
        if key not in self.value:
            if required:
                self.fail("a value (missing key)", key)
            return default
        return self.value[key]

    def at(self, key, default=None, required=True):
        value = self.raw(key, default, required)
        return ConfigReader(value, f"{self.pointer}/{key}", self.source)

    def number(self, key, default=None, positive=False, minimum=None, maximum=None):
        v = self.raw(key, default, required=default is None)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            self.fail("a finite number", key)
        if positive and not v > 0:
            self.fail("a positive number", key)
        if minimum is not None and v < minimum:
            self.fail(f"a number >= {minimum}", key)
        if maximum is not None and v > maximum:
            self.fail(f"a number <= {maximum}", key)
        return float(v)

    def integer(self, key, default=None, minimum=None, maximum=None):
        v = self.raw(key, default, required=default is None)
        if isinstance(v, bool) or not isinstance(v, int):
            self.fail("an integer", key)
        if minimum is not None and v < minimum:
            self.fail(f"an integer >= {minimum}", key)
        if maximum is not None and v > maximum:
            self.fail(f"an integer <= {maximum}", key)
        return v

    def boolean(self, key, default=None):
        v = self.raw(key, default, required=default is None)
        if not isinstance(v, bool):
            self.fail("true or false", key)
        return v

    def string(self, key, default=None):
        v = self.raw(key, default, required=default is None)
        if not isinstance(v, str) or not v:
            self.fail("a non-empty string", key)
        return v

    def choice(self, key, choices, default=None):
        v = self.raw(key, default, required=default is None)
        if v not in choices:
            self.fail("one of " + ", ".join(f'"{c}"' for c in choices), key)
        return v

    def vector(self, key, length, allow_null=False, default=None):
        v = self.raw(key, default, required=default is None)
        ok = isinstance(v, list) and len(v) == length and all(
            (allow_null and x is None)
            or (not isinstance(x, bool) and isinstance(x, (int, float)) and math.isfinite(x))
            for x in v)
        if not ok:
            what = "numbers or null" if allow_null else "finite numbers"
            self.fail(f"an array of {length} {what}", key)
        return [None if x is None else float(x) for x in v]

    def reject_unknown(self):
        if isinstance(self.value, dict):
            unknown = sorted(set(self.value) - self._read)
            if unknown:
                self.fail("no key \"" + unknown[0] + "\" (unknown; known: "
                          + ", ".join(sorted(self._read)) + ")")
