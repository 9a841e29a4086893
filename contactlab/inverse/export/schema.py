"""The FIT.json schema: what :func:`~contactlab.inverse.export_dem` accepts from a fit file.

A fit file comes from another lab by mail or a shared drive, so nothing in it is trusted:
before any of it reaches a DEM deck, :func:`check_fit` checks every entry's type, that
every number is finite and physical, that every name is one the fitted law defines and
every unit the one :data:`~contactlab.inverse.fit_models.FIT_MODELS` gives. The writers
then print only checked numbers, names and units from the code, never text from the file
(``docs/security.md``).
"""

import numbers

from contactlab.errors import ParameterError
from contactlab.inverse.fit_models import FIT_MODELS
from contactlab.inverse.fit_result import FORMAT
from contactlab.laws import LAWS
from contactlab.validation import check_choice, check_number, check_text

__all__ = ["FIT_KEYS", "check_fit"]

EXPORTED_LAWS = tuple(name for name, cls in LAWS.items() if "dem_export" in vars(cls))
"""Fitted laws the DEM codes take as they are: those stating a ``dem_export`` family."""

NUISANCE_UNITS = {"velocity": "m/s", "onset": "s"}
"""Fitted quantities beside the law's parameters, with their units."""

FIT_KEYS = (
    "format",
    "law",
    "law_parameters",
    "parameters",
    "fixed",
    "velocity [m/s]",
    "velocity_measured",
    "onset [s]",
    "grain",
    "sensor",
    "goodness_of_fit",
    "quality",
    "baseline_offset",
    "rebound_on_wall",
    "contact_time_on_sensor [s]",
    "restitution_on_sensor [-]",
    "not_identifiable",
    "baseline_status",
    "baseline_notes",
)
"""Top-level keys of a FIT.json (:meth:`ContactFit.to_dict`; ``quality``, ``baseline_offset``,
``rebound_on_wall``, ``baseline_status`` and ``baseline_notes`` are optional, as files
written before they existed lack them; the last two are read, never exported)."""

PHYSICAL_RANGES = {
    # name: keyword arguments of check_number for a physical value
    "stiffness": {"low": 0.0},
    "damping": {"low": 0.0, "low_open": False},
    "effective_modulus": {"low": 0.0},
    "restitution": {"low": 0.0, "high": 1.0},
    "velocity": {"low": 0.0},
    "onset": {},
    "baseline_offset": {"low": None},
}
"""Allowed range of each exported quantity (SI units; ``low`` excluded unless stated)."""

REQUIRED_KEYS = ("law", "grain", "law_parameters", "parameters", "velocity [m/s]")

GRAIN_KEYS = {
    # key: (required, low bound, high bound); None = unbounded
    "diameter [m]": (True, 0.0, None),
    "density [kg/m^3]": (True, 0.0, None),
    "mass [kg]": (True, 0.0, None),
    "youngs_modulus [Pa]": (False, 0.0, None),
    "poisson_ratio [-]": (False, -1.0, 0.5),
}


def _mapping(value, field):
    if not isinstance(value, dict):
        raise ParameterError(f"{field} must be a JSON object; got {type(value).__name__}")
    return value


def _keys(data, allowed, field):
    for key in data:
        check_text(f"{field} key", key)
        if key not in allowed:
            raise ParameterError(
                f"{field}: unknown key {key!r}; a contactlab fit has {', '.join(allowed)}"
            )


def _numbers_or_flags(data, field):
    """A mapping of names to numbers, booleans or null (goodness of fit, sensor).

    Types only: these entries are never written into a deck, and a fit may hold a NaN
    R squared (flat signal) or a rigid sensor's infinite mass.
    """
    for key, value in _mapping(data, field).items():
        check_text(f"{field} key", key)
        if value is not None and not isinstance(value, numbers.Real):
            raise ParameterError(
                f"{field}[{key!r}] must be a number, true, false or null; got {value!r}"
            )


QUALITY_SHAPE = {
    "consistent": bool,
    "reasons": [str],
    "reduced_chi_squared [-]": numbers.Real,
    "degrees_of_freedom": numbers.Real,
    "noise_samples": numbers.Real,
    "p_value [-]": numbers.Real,
    "whiteness": {
        "test": str,
        "lags": numbers.Real,
        "statistic [-]": numbers.Real,
        "p_value [-]": numbers.Real,
        "noise_p_value [-]": numbers.Real,
    },
    "noise_window [s]": [numbers.Real],
    "alpha [-]": numbers.Real,
}
"""The ``quality`` block as :meth:`contactlab.inverse.fit_quality.FitQuality.to_dict` writes
it: each key's type (a number may be null), lists as ``[type]``, objects as dicts."""

REBOUND_SHAPE = {"fitted_law [-]": numbers.Real, "overlap_end [-]": numbers.Real}
"""The ``rebound_on_wall`` block (:attr:`contactlab.inverse.fit_result.ContactFit.rebound`)."""


def _shaped(value, shape, field):
    """Check a judgement block against its shape (types only: it is reported, never
    written into a deck); unknown keys are refused, missing ones allowed (older files)."""
    if isinstance(shape, dict):
        _keys(_mapping(value, field), tuple(shape), field)
        for key, item in value.items():
            _shaped(item, shape[key], f"{field}[{key!r}]")
    elif isinstance(shape, list):
        if not isinstance(value, list):
            raise ParameterError(f"{field} must be a list; got {type(value).__name__}")
        for i, item in enumerate(value):
            _shaped(item, shape[0], f"{field}[{i}]")
    elif shape is str:
        if not isinstance(value, str):
            raise ParameterError(f"{field} must be a text; got {type(value).__name__}")
        check_text(field, value)
    elif shape is bool:
        if not isinstance(value, bool):
            raise ParameterError(f"{field} must be true or false; got {value!r}")
    elif value is not None and (isinstance(value, bool) or not isinstance(value, shape)):
        raise ParameterError(f"{field} must be a number or null; got {value!r}")


def _check_grain(grain, where):
    grain = _mapping(grain, f"{where}: grain")
    _keys(grain, tuple(GRAIN_KEYS), f"{where}: grain")
    for key, (required, low, high) in GRAIN_KEYS.items():
        if key not in grain or grain[key] is None:
            if required:
                raise ParameterError(f"{where}: grain has no {key!r} (not a contactlab fit)")
            continue
        check_number(f"{where}: grain[{key!r}]", grain[key], low=low, high=high)


def _check_entry(name, entry, unit, where, field=None):
    """One fitted parameter: value, stderr, ci95, unit, identifiable (``field`` names it in
    messages; ``parameters[name]`` by default)."""
    field = field or f"{where}: parameters[{name!r}]"
    entry = _mapping(entry, field)
    _keys(entry, ("value", "stderr", "ci95", "unit", "identifiable"), field)
    if "value" not in entry:
        raise ParameterError(f"{field} has no 'value'")
    check_number(f"{field}['value']", entry["value"], **PHYSICAL_RANGES[name])
    if entry.get("stderr") is not None:
        check_number(f"{field}['stderr']", entry["stderr"], low=0.0, low_open=False)
    ci95 = entry.get("ci95", [None, None])
    if not isinstance(ci95, list) or len(ci95) != 2:
        raise ParameterError(f"{field}['ci95'] must be a list of two numbers or nulls")
    for bound in ci95:
        if bound is not None:
            check_number(f"{field}['ci95']", bound)
    if "unit" in entry and entry["unit"] != unit:
        check_text(f"{field}['unit']", entry["unit"])
        raise ParameterError(f"{field}['unit'] must be {unit!r}; got {entry['unit']!r}")
    if not isinstance(entry.get("identifiable", True), bool):
        raise ParameterError(f"{field}['identifiable'] must be true or false")


def check_fit(data, where):
    """Check a FIT.json dict against the schema before any of it is used.

    Parameters
    ----------
    data : dict
        The fit file's contents (:func:`~contactlab.inverse.export.read_fit`).
    where : str
        Names the fit in messages (its path); checked as printable one-line text.

    Returns
    -------
    dict
        ``data`` itself, now known to hold only the keys above, with finite numbers in
        range, the law's own parameter names and units.

    Raises
    ------
    ParameterError
        Naming the field (``grain['mass [kg]']``, ``parameters['stiffness']['unit']``, ...).
    """
    where = check_text("source", where)
    data = _mapping(data, f"{where}: the fit")
    _keys(data, FIT_KEYS, where)
    for key in REQUIRED_KEYS:
        if key not in data:
            raise ParameterError(f"{where}: missing {key!r} (not a contactlab fit)")
    if "format" in data and data["format"] != FORMAT:
        check_text(f"{where}: format", data["format"])
        raise ParameterError(f"{where}: format must be {FORMAT!r}; got {data['format']!r}")
    law = data["law"]
    if law not in EXPORTED_LAWS:
        check_text(f"{where}: law", law)
        raise ParameterError(
            f"{where}: export of law {law!r} is not supported; fit one of "
            f"{list(EXPORTED_LAWS)} for the DEM codes"
        )
    model = FIT_MODELS[law]
    units = dict(zip(model.parameters, model.units, strict=True))
    for name, value in _mapping(data["law_parameters"], f"{where}: law_parameters").items():
        check_text(f"{where}: law_parameters key", name)
        check_number(f"{where}: law_parameters[{name!r}]", value, low=0.0, low_open=False)
    parameters = _mapping(data["parameters"], f"{where}: parameters")
    _keys(parameters, (*model.parameters, *NUISANCE_UNITS), f"{where}: parameters")
    for name, entry in parameters.items():
        _check_entry(name, entry, {**units, **NUISANCE_UNITS}[name], where)
    fixed = _mapping(data.get("fixed", {}), f"{where}: fixed")
    _keys(fixed, model.parameters, f"{where}: fixed")
    for name, value in fixed.items():
        check_number(f"{where}: fixed[{name!r}]", value, **PHYSICAL_RANGES[name])
    check_number(f"{where}: velocity [m/s]", data["velocity [m/s]"], low=0.0, unit="m/s")
    _check_grain(data["grain"], where)
    for key in ("goodness_of_fit", "sensor"):
        if key in data:
            _numbers_or_flags(data[key], f"{where}: {key}")
    for key, shape in (("quality", QUALITY_SHAPE), ("rebound_on_wall", REBOUND_SHAPE)):
        if key in data:
            _shaped(data[key], shape, f"{where}: {key}")
    if "baseline_offset" in data:
        field = f"{where}: baseline_offset"
        _check_entry("baseline_offset", data["baseline_offset"], "N", where, field)
    for key in ("onset [s]", "contact_time_on_sensor [s]", "restitution_on_sensor [-]"):
        if data.get(key) is not None:
            check_number(f"{where}: {key}", data[key], low=None)
    if not isinstance(data.get("velocity_measured", False), bool):
        raise ParameterError(f"{where}: velocity_measured must be true or false")
    if not isinstance(data.get("baseline_status", ""), str):
        raise ParameterError(f"{where}: baseline_status must be text")
    check_text(f"{where}: baseline_status", data.get("baseline_status", ""))
    notes = data.get("baseline_notes", [])
    if not isinstance(notes, list) or not all(isinstance(note, str) for note in notes):
        raise ParameterError(f"{where}: baseline_notes must be a list of texts")
    for note in notes:
        check_text(f"{where}: baseline_notes", note)
    not_identifiable = data.get("not_identifiable", [])
    if not isinstance(not_identifiable, list):
        raise ParameterError(f"{where}: not_identifiable must be a list of parameter names")
    for name in not_identifiable:
        check_choice(f"{where}: not_identifiable", name, (*model.parameters, *NUISANCE_UNITS))
    return data
