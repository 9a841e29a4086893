"""contactlab: grain impact on force sensors."""
