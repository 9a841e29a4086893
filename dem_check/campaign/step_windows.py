"""Whether a step found on the period means lies inside its search window (step 5 of
:mod:`dem_check.campaign.steps`)."""

__all__ = ["placed_inside"]


def placed_inside(index, window, n, period):
    """Whether a step placed at ``index`` lies a sensor period or more inside its
    ``window`` ``(first, stop)`` from each end that is not the record's (``n`` samples).

    The window spans half a window of blocks either side of the boundary whose level
    change is the largest; a step moves the change most at its own boundary, so it lies
    inside. Placed at a window's end, the samples within it are at one level and the
    change came from blocks beyond it: the medians of a window that reaches past a
    masked impact read that impact's slow ringing (the plate's), or a weak impact in
    it, as a level change (issue 22: seeds 11, 92, 164 and 304 of
    :func:`dem_check.campaign.drawn_records.weak_in_ringing`, 0.1-0.14 N at 10-49
    sigmas, each placed at its window's end).
    """
    first, stop = window
    return (first == 0 or index - first >= period) and (stop == n or stop - index >= period)
