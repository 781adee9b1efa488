"""Running robosolve: solve one file, split a solve over two cores, the local / Dask back-ends,
output folders, golden comparison, interrupts. Returns typed records; prints nothing (the CLI
package, robosolve/cli/, prints them)."""
