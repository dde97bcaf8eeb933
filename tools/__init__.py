"""Developer tools of the repository (not shipped): scripts, and what the tests and the benchmarks
share without importing each other."""
