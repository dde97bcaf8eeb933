"""Results Datasets (results-schema.md): the variable registry, the quasi-static builder, NetCDF
input/output and the validity checks (:func:`solver.results.checks.result_warnings`)."""
