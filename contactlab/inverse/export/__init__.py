"""Write a fitted contact law as input for DEM codes: LAMMPS, LIGGGHTS, MercuryDPM, YADE, EDEM.

Each writer turns a fit (a :class:`~contactlab.inverse.fit.ContactFit` or its FIT.json
dict) into a commented snippet in the code's own parameter names and SI units, with the
time step the code's guidance picks. Two law families are exported:

* linear spring-dashpot (``linear``): stiffness ``k`` [N/m] and damping ``c`` [N*s/m]
  go in directly where the code takes them (LIGGGHTS ``hooke/stiffness`` with absolute
  damping, MercuryDPM ``LinearViscoelasticSpecies``, YADE ``ViscElMat``); EDEM's Linear
  Spring takes the restitution, converted with the codes' overlap-convention formula.
* damped Hertz (``hertz_damped``, ``hertz``): the effective modulus ``E*`` of the
  grain-plate contact and the restitution ``e`` of the Tsuji mapping, which LIGGGHTS
  (``model hertz``), YADE (``Ip2_FrictMat_FrictMat_MindlinPhys(en=...)``), EDEM
  (Hertz-Mindlin no slip) and MercuryDPM (``setElasticModulusAndRestitutionCoefficient``)
  all implement as ``kH d**1.5 + sqrt(5) beta sqrt(m* kH) d**0.25 d'``. The grain's
  Young's modulus follows from ``1/E* = (1-nu**2)/E + (1-nu_p**2)/E_p`` with the plate's
  (steel by default).

Friction, rolling resistance and tangential stiffness are not fitted by a normal impact:
where a code requires them the snippet writes a placeholder marked ``NOT FITTED``.
"""

from contactlab.inverse.export import edem, kratos, lammps, liggghts, mercurydpm, yade
from contactlab.inverse.export.contact import (
    STEEL_POISSON_RATIO,
    STEEL_YOUNGS_MODULUS,
    contact_from_fit,
    read_fit,
)
from contactlab.validation import check_choice, check_poisson_ratio, check_positive

__all__ = ["DEM_CODES", "export_dem", "read_fit"]

DEM_CODES = {
    "lammps": lammps.write,
    "liggghts": liggghts.write,
    "mercurydpm": mercurydpm.write,
    "yade": yade.write,
    "edem": edem.write,
    "kratos": kratos.write,
}
"""Export targets: code name -> writer (one module per code)."""


def export_dem(
    fit,
    code,
    *,
    source="contactlab fit",
    poisson_ratio=None,
    plate_youngs_modulus=STEEL_YOUNGS_MODULUS,
    plate_poisson_ratio=STEEL_POISSON_RATIO,
    friction=None,
):
    """Input snippet for a DEM code from a fitted contact law.

    Parameters
    ----------
    fit : ContactFit or dict
        A fit, or the dict of a FIT.json (:func:`read_fit`). Law parameters held fixed
        in the fit (its ``fixed``) are exported like fitted ones.
    code : {"lammps", "liggghts", "mercurydpm", "yade", "edem"}
        Target code.
    source : str, default "contactlab fit"
        Named in the snippet's header (e.g. the FIT.json path).
    poisson_ratio : float, optional
        Grain Poisson ratio [-] (Hertz laws); default the fit's grain value.
    plate_youngs_modulus : float, default 210e9
        Sensor plate's Young's modulus [Pa] (steel).
    plate_poisson_ratio : float, default 0.3
        Sensor plate's Poisson ratio [-] (steel).
    friction : float, optional
        Friction coefficient [-]; without it a placeholder marked NOT FITTED is written.

    Returns
    -------
    str
        The snippet, comments in the code's syntax, ending in a newline.

    Notes
    -----
    Time steps follow each code's guidance (module constants): a fiftieth of the contact
    time for linear laws and for MercuryDPM's Hertz (MercuryDPM's habit), 10 % of the
    Rayleigh time for LIGGGHTS' Hertz,
    20 % for EDEM, ``0.5 PWaveTimeStep()`` for YADE's Hertz and ``0.05 tc`` for its
    ViscElMat. The contact time is that of the fitted law on a rigid plate at the fitted
    velocity. The Rayleigh time is ``pi R sqrt(rho/G) / (0.1631 nu + 0.8766)``.

    References
    ----------
    Tsuji Y., Tanaka T., Ishida T. (1992) Powder Technol. 71, 239-250.
    DOI 10.1016/0032-5910(92)88030-L (damping from restitution).
    Antypov D., Elliott J.A. (2011) EPL 94, 50004. DOI 10.1209/0295-5075/94/50004
    """
    code = check_choice("code", code, tuple(DEM_CODES))
    # checked here, not only where a Hertz fit uses them: a linear fit ignores them, but a
    # NaN or a text there is a mistake to report, not to pass over
    if poisson_ratio is not None:
        check_poisson_ratio("poisson_ratio", poisson_ratio)
    check_positive("plate_youngs_modulus", plate_youngs_modulus, "Pa")
    check_poisson_ratio("plate_poisson_ratio", plate_poisson_ratio)
    contact = contact_from_fit(
        fit, source, poisson_ratio, plate_youngs_modulus, plate_poisson_ratio, friction
    )
    return "\n".join(DEM_CODES[code](contact)) + "\n"
