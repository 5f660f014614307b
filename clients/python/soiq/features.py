"""The text form of the features a query filters, selects and orders by, as `soiq query` and
soiqd's /soiq/v1/query write them (proto/text/feature_expression.h is the reference):

    feature   := NAME | NAME[REGION] | NAME[REGION,IMAGE] | NAME[,IMAGE] | asym(feature)
    predicate := feature OP NUMBER        OP one of < <= > >= == !=

"voxel_volume_mm3", "mean[shell:5,PT]", "asym(voxel_volume_mm3) < -0.05". Whether NAME is a known
feature is soiqd's to say (InvalidArgument naming the nearest one).
"""

import re

from soiq.errors import InvalidArgument
from soiq.v1 import soiq_pb2

_OPS = {"<": soiq_pb2.LT, "<=": soiq_pb2.LE, ">": soiq_pb2.GT, ">=": soiq_pb2.GE, "==": soiq_pb2.EQ, "!=": soiq_pb2.NE}
_FEATURE = re.compile(r"^\s*([A-Za-z][A-Za-z0-9_]*)\s*(?:\[\s*([^\],\s]*)\s*(?:,\s*([A-Za-z0-9._-]+)\s*)?\])?\s*$")
_ASYM = re.compile(r"^\s*asym\s*\((.*)\)\s*$")
_PREDICATE = re.compile(r"^(.*?)(<=|>=|==|!=|<|>)\s*([-+0-9.eE]+)\s*$")


def parse_feature(text):
    """A soiq_pb2.FeatureRef from its text; InvalidArgument saying what is wrong."""
    if isinstance(text, soiq_pb2.FeatureRef):
        return text
    asym = _ASYM.match(text)
    if asym:
        inner = parse_feature(asym.group(1))
        if inner.asymmetry:
            raise InvalidArgument("asym() of asym() in '%s'" % text)
        inner.asymmetry = True
        return inner
    m = _FEATURE.match(text)
    if not m:
        raise InvalidArgument("'%s' is not a feature: NAME, NAME[REGION], NAME[REGION,IMAGE] or asym(FEATURE)" % text)
    return soiq_pb2.FeatureRef(name=m.group(1), region=m.group(2) or "", image=m.group(3) or "")


def parse_predicate(text):
    """A soiq_pb2.Predicate from 'FEATURE OP NUMBER'."""
    if isinstance(text, soiq_pb2.Predicate):
        return text
    m = _PREDICATE.match(text)
    if not m:
        raise InvalidArgument("'%s' is not a condition: FEATURE OP NUMBER with OP one of < <= > >= == !=" % text)
    try:
        value = float(m.group(3))
    except ValueError:
        raise InvalidArgument("'%s' is not a number in '%s'" % (m.group(3), text)) from None
    return soiq_pb2.Predicate(feature=parse_feature(m.group(1)), op=_OPS[m.group(2)], value=value)


def feature_text(feature):
    """The canonical text of a FeatureRef, as `soiq query` heads its columns: "mean[shell:5,PT]"."""
    if feature.asymmetry:
        inner = soiq_pb2.FeatureRef()
        inner.CopyFrom(feature)
        inner.asymmetry = False
        return "asym(%s)" % feature_text(inner)
    if not feature.region and not feature.image:
        return feature.name
    if not feature.image:
        return "%s[%s]" % (feature.name, feature.region)
    return "%s[%s,%s]" % (feature.name, feature.region, feature.image)
