"""The projected residual of :func:`contactlab.inverse.ringdown.refine_poles` one window
after the other, as it was before the windows were stacked (session 17): the reference
that ``tests/contactlab/inverse/test_ringdown.py`` checks the stacked one against and
that ``benchmarks/bench_refine_poles.py`` times it against (imported by name:
``tests/conftest.py`` and the benchmark put this folder on the path)."""

import numpy as np

from contactlab.inverse.ringdown import _Projection


class LoopProjection(_Projection):
    """The projected residual of ``refine_poles`` and its Jacobian at ``x`` (damping
    ratio and frequency over its start for each pole), one window after the other (the
    poles and their rates as the stacked one reads them; its residual and Jacobian are
    this class's own)."""

    def __init__(self, windows, scale):
        self.windows, self.scale, self.x, self.parts = windows, scale, None, None

    def _update(self, x):
        if self.x is not None and np.array_equal(x, self.x):
            return
        b, sigma, dsigma = self.rates(x)
        residuals, jacobians = [], []
        for tau, y in self.windows:
            decay = np.exp(np.outer(tau, sigma))
            cos, sin = decay * np.cos(np.outer(tau, b)), decay * np.sin(np.outer(tau, b))
            design = np.column_stack([np.ones(tau.size), tau, cos, sin])
            q, r = np.linalg.qr(design)
            coefficients = np.linalg.lstsq(r, q.T @ y, rcond=None)[0]
            residual = y - design @ coefficients
            c, d = coefficients[2 : 2 + b.size], coefficients[2 + b.size :]
            model = cos * c + sin * d  # each pole's part of the model, one column each
            turned = cos * d - sin * c  # its derivative along b over tau
            derivative = np.empty((tau.size, x.size))
            derivative[:, 0::2] = tau[:, None] * model * dsigma[:, 0]
            derivative[:, 1::2] = tau[:, None] * (model * dsigma[:, 1] + turned * self.scale)
            # Kaufman: the residual's Jacobian less the term of the amplitudes' change
            jacobians.append(-(derivative - q @ (q.T @ derivative)))
            residuals.append(residual)
        self.x, self.parts = x.copy(), (np.concatenate(residuals), np.concatenate(jacobians))
