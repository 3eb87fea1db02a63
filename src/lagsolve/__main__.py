from lagsolve.cli import main

main()
