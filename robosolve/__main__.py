from robosolve.cli import main

main()
