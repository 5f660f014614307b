"""The options of a two-stage query in Python: proto/text/query_options.h's table (the one the
command line and the HTTP query read), with Python's names (min_age for --min-age and min-age=).
Held to that table by the shared cases of tests/data/shared_cases/query_options.json: the same
options in the same order, the same requests, the same refusals.

Each option reads one value into a soiq_pb2.QueryRequest, checked by the rule of its field as
core/base/field_rules.h states it; the rules between options are check_request's.
"""

import datetime
import math

from soiq.errors import InvalidArgument
from soiq.features import _NUMBER, feature_text, parse_feature, parse_predicate
from soiq.v1 import soiq_pb2

_MAX_ID_BYTES = 64
_MAX_NAME_BYTES = 256


def _text(value, max_bytes):
    value = str(value)
    if len(value.encode("utf-8", "surrogatepass")) > max_bytes:
        raise ValueError("'%s' is %d bytes long; the limit is %d" % (value[:40], len(value.encode()), max_bytes))
    if any(ord(c) < 0x20 or ord(c) == 0x7F for c in value):
        raise ValueError("'%s' contains a control character (newline, tab, ...)" % value[:40])
    try:
        value.encode("utf-8")
    except UnicodeEncodeError:
        raise ValueError("'%s' is not UTF-8 text" % value[:40]) from None
    return value


def _date(value):
    value = str(value)
    try:
        ok = len(value) == 8 and value.isdigit() and datetime.date(int(value[:4]), int(value[4:6]), int(value[6:]))
    except ValueError:
        ok = False
    if value and not ok:
        raise ValueError("'%s' is not a calendar date YYYYMMDD" % value[:40])
    return value


def _number(value):
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        number = float(value)
    else:  # text as strtod reads it, as the table does
        if not _NUMBER.fullmatch(str(value)):
            raise ValueError("'%s' is not a number" % str(value)[:40])
        number = float(value)
    if not math.isfinite(number):
        raise ValueError("'%s' is not a number" % value)
    return number


def _years(value):
    years = _number(value)
    if not 0 <= years < 200:
        raise ValueError("%g is not an age in years (at least 0, under 200)" % years)
    return years


def _whole(value, lo, hi):
    try:
        number = _number(value)
    except ValueError:
        number = None
    if number is None or number != math.floor(number) or not lo <= number <= hi:
        raise ValueError("'%s' is not a whole number in %d..%d" % (str(value)[:40], lo, hi))
    return int(number)


def _one_of(value, choices, what):
    if value not in choices:
        raise ValueError("'%s' is not %s" % (str(value)[:40], what))
    return value


def _stage1(field, check):
    def apply(value, r):
        setattr(r.stage1, field, check(value))
    return apply


def _spacing(value, r):
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        parts = [value]
    elif isinstance(value, str):
        parts = value.split(",")
    else:
        parts = list(value)
    try:
        xyz = [_number(p) for p in parts]
    except ValueError:
        xyz = []
    if len(xyz) not in (1, 3) or any(s <= 0 for s in xyz):
        raise ValueError("'%s' is not a spacing: S or SX,SY,SZ in mm, each > 0" % (value,))
    if len(xyz) == 1 or xyz[0] == xyz[1] == xyz[2]:
        r.grid.spacing_mm = xyz[0]
    else:
        r.grid.spacing_xyz.CopyFrom(soiq_pb2.SpacingXYZ(x=xyz[0], y=xyz[1], z=xyz[2]))


def _desc(value, r):
    if isinstance(value, str):
        value = _one_of(value, ("true", "false", ""), "true or false") != "false"
    r.descending = bool(value)


def _series_modality(value, r):
    if not value:
        raise ValueError("a modality is required (PT, CT, MR, ...)")
    r.grid.series_modality = _text(value, _MAX_ID_BYTES)


def _interpolation(value, r):
    _one_of(value, ("nearest", "linear"), "nearest or linear")
    r.interpolation = soiq_pb2.LINEAR if value == "linear" else soiq_pb2.NEAREST


# (name as the table spells it, repeatable, apply(value, request)), in the table's order.
OPTIONS = (
    ("patient", False, _stage1("patient_id_glob", lambda v: _text(v, _MAX_NAME_BYTES))),
    ("sex", False, _stage1("sex", lambda v: _one_of(v, ("", "M", "F", "O"), "a sex: M, F or O"))),
    ("min-age", False, _stage1("min_age_years", _years)),
    ("max-age", False, _stage1("max_age_years", _years)),
    ("birth-date-from", False, _stage1("birth_date_from", _date)),
    ("birth-date-to", False, _stage1("birth_date_to", _date)),
    ("study-date-from", False, _stage1("study_date_from", _date)),
    ("study-date-to", False, _stage1("study_date_to", _date)),
    ("modality", False, _stage1("modality", lambda v: _text(v, _MAX_ID_BYTES))),
    ("description", False, _stage1("study_description_glob", lambda v: _text(v, _MAX_NAME_BYTES))),
    ("name", False, _stage1("structure_name_glob", lambda v: _text(v, _MAX_NAME_BYTES))),
    ("laterality", False, _stage1("laterality", lambda v: _one_of(v, ("", "L", "R"), "a laterality: L or R"))),
    ("where", True, lambda v, r: r.where.append(parse_predicate(v))),
    ("select", True, lambda v, r: r.select.append(parse_feature(v))),
    ("order-by", False, lambda v, r: r.order_by.CopyFrom(parse_feature(v))),
    ("desc", False, _desc),
    ("limit", False, lambda v, r: setattr(r, "limit", _whole(v, 1, 1 << 30))),
    ("spacing", False, _spacing),
    ("margin", False, lambda v, r: setattr(r.grid, "margin_voxels", _whole(v, 0, 1000))),
    ("series-modality", False, _series_modality),
    ("interpolation", False, _interpolation),
)
_BY_NAME = {name: (repeatable, apply) for name, repeatable, apply in OPTIONS}


def python_name(name):
    """How Python spells an option: min_age for min-age."""
    return name.replace("-", "_")


def query_request(options):
    """A soiq_pb2.QueryRequest from (name, value) pairs in the table's spelling ("min-age", "40"),
    values as text or as Python numbers, lists and booleans. InvalidArgument naming the option in
    Python's spelling (min_age) otherwise."""
    request = soiq_pb2.QueryRequest()
    given = set()
    for name, value in options:
        if name not in _BY_NAME:
            raise InvalidArgument("unknown query option '%s' (known: %s)" % (
                python_name(name), ", ".join(python_name(n) for n, _, _ in OPTIONS)))
        repeatable, apply = _BY_NAME[name]
        if not repeatable and name in given:
            raise InvalidArgument("%s is given twice" % python_name(name))
        given.add(name)
        try:
            apply(value, request)
        except (ValueError, InvalidArgument) as e:
            raise InvalidArgument("%s %r: %s" % (python_name(name), value, e)) from None
    _check_request(request, given)
    return request


def _check_request(r, given):
    """The rules between options, as QueryRequestBuilder::finish states them."""
    if r.descending and not r.HasField("order_by"):
        raise InvalidArgument("desc needs order_by")
    if "spacing" in given and "series-modality" in given:
        raise InvalidArgument("give either spacing or series_modality, not both")
    if "margin" in given and "spacing" not in given:
        raise InvalidArgument("margin goes with spacing")
    s = r.stage1
    if s.HasField("min_age_years") and s.HasField("max_age_years") and s.min_age_years > s.max_age_years:
        raise InvalidArgument("min_age is above max_age")


STRUCTURE_COLUMNS = ("id", "patient_id", "study_uid", "name", "laterality")


def query_columns(request):
    """The answer's columns as every face heads them (proto/text/query_columns.h): the structure's,
    then each feature once, at its first place among where's, select's and order_by's; with, for
    each feature column, the index of its value in a row's values."""
    texts = [feature_text(p.feature) for p in request.where] + [feature_text(f) for f in request.select]
    if request.HasField("order_by"):
        texts.append(feature_text(request.order_by))
    header, value_at = list(STRUCTURE_COLUMNS), []
    for i, text in enumerate(texts):
        if text not in header[len(STRUCTURE_COLUMNS):]:
            header.append(text)
            value_at.append(i)
    return header, value_at
