"""Reading and running grainflow from Python.

Modules (import the one you need; this package itself imports nothing, so `grainflow.vtp` works
without numpy):

  grainflow.outputs    a run folder into numpy arrays: Run(folder).series, .surface, .summary,
                       .final_state(), .residence(), .layers(), .frames(); read_frame(path), read_csv(path),
                       rows_of(table) (a table as a list of rows)
  grainflow.run        run_scene(scene, out, sets=..., steps=...): runs the grainflow binary, returns a Run
  grainflow.vtp        read_vtp(path): a frame's arrays as lists, without numpy
  grainflow.resumable  a long run in pieces of a wall-time budget, archived and restored across checkouts
  grainflow.long_run   `python3 -m grainflow.long_run SCENE --out DIR --archive DIR`: one such run
"""

__version__ = "0.1.0"
