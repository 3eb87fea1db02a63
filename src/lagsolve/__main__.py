from lagsolve.cli import run

run()
