"""make_folder: the output folder of SweepResult.to_csv and CampaignResult.write."""

import pytest

from contactlab.errors import ParameterError
from contactlab.validation import make_folder


def test_the_folder_and_its_parents_are_made_and_returned_as_a_path(tmp_path):
    folder = make_folder("out", str(tmp_path / "a" / "b"))
    assert folder == tmp_path / "a" / "b" and folder.is_dir()
    assert make_folder("out", folder) == folder  # an existing folder is fine


@pytest.mark.parametrize("value", [5, None, ""])
def test_what_is_not_a_path_is_refused_by_name(tmp_path, value):
    with pytest.raises(ParameterError, match="directory must be a file path"):
        make_folder("directory", value)
