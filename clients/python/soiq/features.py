"""The text form of the features a query filters, selects and orders by, as `soiq query` and
soiqd's /soiq/v1/query read them. proto/text/feature_expression.h is the reference; this parser
follows it rule for rule and is held to it by the shared cases of
tests/data/shared_cases/feature_expressions.json (the same texts accepted as the same messages,
the same texts refused at the same column):

    feature   := NAME | NAME[REGION] | NAME[REGION,IMAGE] | NAME[,IMAGE] | asym(feature)
    predicate := feature OP NUMBER        OP one of < <= > >= == !=
    NAME   letters, digits and '_', starting with a letter
    REGION inside, shell:R or core:R with R > 0 in mm
    IMAGE  a modality ("PT") or a series uid: letters, digits, '.', '-', '_'

"voxel_volume_mm3", "mean[shell:5,PT]", "asym(voxel_volume_mm3) < -0.05". Whether NAME is a known
feature is soiqd's to say (InvalidArgument naming the nearest one).
"""

import math
import re

from soiq.errors import InvalidArgument
from soiq.v1 import soiq_pb2

# The symbols of soiq's comparisons (core/base/comparison.h), two-character ones first.
_OPS = (("<=", soiq_pb2.LE), (">=", soiq_pb2.GE), ("==", soiq_pb2.EQ), ("!=", soiq_pb2.NE), ("<", soiq_pb2.LT),
        (">", soiq_pb2.GT))
_SYMBOL = {op: symbol for symbol, op in _OPS}
# What C's strtod reads as a finite decimal number, whole: no '_', no 'inf' or 'nan'.
_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")


def _ascii_alnum(c):
    return c.isascii() and c.isalnum()


class _Parser:
    """A cursor over the text; every error names the column (from 1) it stopped at."""

    def __init__(self, text):
        self.text = text
        self.pos = 0

    def error(self, what):
        return InvalidArgument("%s at column %d of '%s'" % (what, self.pos + 1, self.text))

    def skip_blanks(self):
        while self.pos < len(self.text) and self.text[self.pos] in " \t\n\r\f\v":
            self.pos += 1

    def at_end(self):
        self.skip_blanks()
        return self.pos == len(self.text)

    def accept(self, token):
        self.skip_blanks()
        if self.text.startswith(token, self.pos):
            self.pos += len(token)
            return True
        return False

    def take(self, ok):
        self.skip_blanks()
        start = self.pos
        while self.pos < len(self.text) and ok(self.text[self.pos]):
            self.pos += 1
        return self.text[start:self.pos]


def _check_region(region, p):
    if region == "inside":
        return
    for prefix in ("shell:", "core:"):
        if region.startswith(prefix):
            radius = region[len(prefix):]
            if not (_NUMBER.fullmatch(radius) and math.isfinite(float(radius)) and float(radius) > 0):
                raise p.error("region '%s' needs a radius > 0 mm, like %s5" % (region, prefix))
            return
    raise p.error("unknown region '%s' (use inside, shell:R or core:R)" % region)


def _feature_at(p, inside_asym):
    f = soiq_pb2.FeatureRef()
    p.skip_blanks()
    start = p.pos
    if p.accept("asym"):
        if p.accept("("):
            if inside_asym:
                p.pos = start
                raise p.error("asym() cannot be nested")
            f = _feature_at(p, True)
            if not p.accept(")"):
                raise p.error("expected ')' closing asym(")
            f.asymmetry = True
            return f
        p.pos = start  # a feature whose name starts with "asym"
    if p.pos >= len(p.text) or not (p.text[p.pos].isascii() and p.text[p.pos].isalpha()):
        raise p.error("expected a feature name")
    f.name = p.take(lambda c: _ascii_alnum(c) or c == "_")
    if not p.accept("["):
        return f
    p.skip_blanks()
    region_at = p.pos
    region = p.take(lambda c: _ascii_alnum(c) or c in ":._")
    if region:
        after = p.pos
        p.pos = region_at
        _check_region(region, p)
        p.pos = after
        f.region = region
    if p.accept(","):
        image = p.take(lambda c: _ascii_alnum(c) or c in ".-_")
        if not image:
            raise p.error("expected an image (a modality like PT or a series uid)")
        f.image = image
    elif not region:
        raise p.error("expected a region (inside, shell:R, core:R) or ',IMAGE'")
    if not p.accept("]"):
        raise p.error("expected ']'")
    return f


def parse_feature(text):
    """A soiq_pb2.FeatureRef from its text; InvalidArgument saying what is wrong and where."""
    if isinstance(text, soiq_pb2.FeatureRef):
        return text
    p = _Parser(text)
    f = _feature_at(p, False)
    if not p.at_end():
        raise p.error("unexpected text after the feature")
    return f


def parse_predicate(text):
    """A soiq_pb2.Predicate from 'FEATURE OP NUMBER'."""
    if isinstance(text, soiq_pb2.Predicate):
        return text
    p = _Parser(text)
    predicate = soiq_pb2.Predicate(feature=_feature_at(p, False))
    for symbol, op in _OPS:
        if p.accept(symbol):
            predicate.op = op
            break
    else:
        raise p.error("expected a comparison (< <= > >= == !=) and a number" if p.at_end()
                      else "expected a comparison (< <= > >= == !=)")
    p.skip_blanks()
    number = p.text[p.pos:].rstrip(" \t\n\r\f\v")
    if not _NUMBER.fullmatch(number) or not math.isfinite(float(number)):
        raise p.error("expected a number")
    predicate.value = float(number)
    return predicate


def feature_text(feature):
    """The canonical text of a FeatureRef, as `soiq query` heads its columns: "mean[shell:5,PT]"."""
    text = feature.name
    if feature.region or feature.image:
        text += "[%s%s]" % (feature.region, "," + feature.image if feature.image else "")
    return "asym(%s)" % text if feature.asymmetry else text


def predicate_text(predicate):
    """'FEATURE OP NUMBER' as the command line writes a condition back: "mean[inside,PT] > 2.5"."""
    return "%s %s %g" % (feature_text(predicate.feature), _SYMBOL.get(predicate.op, "?"), predicate.value)
