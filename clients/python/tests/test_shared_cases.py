"""The Python client against the cases every face of the query language shares
(tests/data/shared_cases/): the query table's options in its order, each accepted case's request
and columns, each refused case refused naming its option in Python's spelling; the feature grammar's
texts accepted as the same messages with the same canonical text, or refused at the same column.
No soiqd needed: these are the client's own parsing."""

import json
import os

import pytest
from google.protobuf import json_format

from soiq import errors
from soiq.features import feature_text, parse_feature, parse_predicate, predicate_text
from soiq.query_options import OPTIONS, python_name, query_columns, query_request
from soiq.v1 import soiq_pb2


def _cases(name):
    with open(os.path.join(os.environ["SOIQ_TEST_DATA"], "shared_cases", name)) as f:
        return json.load(f)


QUERY = _cases("query_options.json")
GRAMMAR = _cases("feature_expressions.json")


def test_the_options_are_the_tables_in_its_order():
    assert [name for name, _, _ in OPTIONS] == QUERY["options"]


@pytest.mark.parametrize("case", QUERY["accepted"], ids=lambda c: json.dumps(c["args"])[:60])
def test_an_accepted_case_makes_its_request_and_columns(case):
    request = query_request([tuple(pair) for pair in case["args"]])
    assert request == json_format.ParseDict(case["request"], soiq_pb2.QueryRequest())
    assert query_columns(request)[0] == case["columns"]


@pytest.mark.parametrize("case", QUERY["refused"], ids=lambda c: json.dumps(c["args"])[:60])
def test_a_refused_case_names_its_option(case):
    with pytest.raises(errors.InvalidArgument) as e:
        query_request([tuple(pair) for pair in case["args"]])
    assert python_name(case["option"]) in str(e.value)


def test_the_client_takes_python_values_as_the_table_takes_text():
    from soiq.client import Client
    request = Client._query_request(["voxel_volume_mm3 > 1000"], "sphericity", "sphericity", True, 5, (1, 1, 2), 3,
                                    "", "linear", {"min_age": 40, "sex": "F", "name": None})
    want = query_request([("sex", "F"), ("min-age", "40"), ("where", "voxel_volume_mm3 > 1000"),
                          ("select", "sphericity"), ("order-by", "sphericity"), ("desc", "true"), ("limit", "5"),
                          ("spacing", "1,1,2"), ("margin", "3"), ("interpolation", "linear")])
    assert request == want
    with pytest.raises(errors.InvalidArgument, match="unknown query filter 'colour'"):
        Client._query_request((), (), None, False, 0, None, None, "", None, {"colour": "red"})


def _check_grammar(kind, key, parse, text_of):
    for case in GRAMMAR[kind]:
        if "error" in case:
            with pytest.raises(errors.InvalidArgument) as e:
                parse(case["text"])
            message = str(e.value)
            assert "at column %d of" % case["column"] in message, (case, message)
            if not case["error"].startswith("did you mean"):  # soiqd's suggestion, not the client's
                assert case["error"] in message, (case, message)
            continue
        got = parse(case["text"])
        want = json_format.ParseDict(case[key], type(got)())
        assert got == want, case
        assert text_of(got) == case["canonical"], case
        assert parse(text_of(got)) == want, case


def test_features_as_the_shared_cases_say():
    _check_grammar("features", "feature", parse_feature, feature_text)


def test_predicates_as_the_shared_cases_say():
    _check_grammar("predicates", "predicate", parse_predicate, predicate_text)
