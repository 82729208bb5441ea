"""The limits the pipeline applies to the JSON it reads, as the C++ readers do (io/limits.hpp):
nesting at most MAX_DEPTH deep. Python's parser recurses once per level, so a document nested
tens of thousands deep ends in a RecursionError traceback instead of a one-line error."""
import json

MAX_DEPTH = 64  # the C++ readers' kMaxJsonDepth


class JsonLimitError(ValueError):
    """A document beyond a limit; the message names the file and the JSON pointer."""


def depth_error(value, source: str):
    """The error for the first value nested deeper than MAX_DEPTH, or None. Iterative, so it
    never recurses itself."""
    stack = [(value, "", 0)]
    while stack:
        v, pointer, depth = stack.pop()
        if isinstance(v, (dict, list)):
            if depth >= MAX_DEPTH:
                return JsonLimitError(f"{source}: {pointer or '/'}: expected arrays and objects nested at most "
                                      f"{MAX_DEPTH} deep, got deeper")
            items = v.items() if isinstance(v, dict) else enumerate(v)
            for k, child in items:
                token = str(k).replace("~", "~0").replace("/", "~1")
                stack.append((child, f"{pointer}/{token}", depth + 1))
    return None


def loads(text: str, source: str):
    """json.loads with the nesting bound; JsonLimitError (a ValueError) names `source`."""
    try:
        value = json.loads(text)
    except RecursionError:
        raise JsonLimitError(f"{source}: /: expected arrays and objects nested at most {MAX_DEPTH} deep, "
                             "got deeper") from None
    err = depth_error(value, source)
    if err:
        raise err
    return value
