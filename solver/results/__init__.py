"""Results Datasets (docs/results-schema.md): the registry (``variables``), the builder shared by
both models (``dataset``; each model's own output lives beside it: solver/models/*/), the
trajectory metrics and settling window (``summary``), NetCDF and CSV files (``io``), the validity
checks (``checks``) and the ``ds.racetrace`` accessor (``accessor``)."""
