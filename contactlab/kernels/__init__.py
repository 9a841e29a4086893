"""The compiled numerical core (numba): one impact loop for the single and batch solvers.

* :mod:`~contactlab.kernels.rules`: the window, scan-step, contact-matrix and
  crossed-side rules;
* :mod:`~contactlab.kernels.impact_loop`: the event loop of a normal impact and its
  headline readings (:func:`~contactlab.kernels.impact_loop.solve_impact`), and the
  batch's loop over rows;
* :mod:`~contactlab.kernels.linear_impact`, :mod:`~contactlab.kernels.hertz_impact`:
  its contact pieces (modal; DOP853 with readings on the dense output);
* :mod:`~contactlab.kernels.modal`: modal pieces, event scans, free flight;
* :mod:`~contactlab.kernels.power`, :mod:`~contactlab.kernels.dop853`,
  :mod:`~contactlab.kernels.power_piece`: the power-law right-hand side, the DOP853
  stepper and the contact piece; :mod:`~contactlab.kernels.brent`: Brent's method;
* :mod:`~contactlab.kernels.oblique_rhs`, :mod:`~contactlab.kernels.oblique_events`,
  :mod:`~contactlab.kernels.oblique_kernel`: the oblique impact's equations, events and
  phase loop (LAMMPS' Coulomb cap); :mod:`~contactlab.kernels.elastic_cap_rhs`,
  :mod:`~contactlab.kernels.elastic_cap`: Kratos' elastic cap's slides and phase loop;
  :mod:`~contactlab.kernels.oblique_sample`: the solved contact's sampler and its
  lever-arm moment;
* :mod:`~contactlab.kernels.gauss`: the composite Gauss-Legendre rule on graded panels
  (:mod:`contactlab.quadrature`'s).
"""
