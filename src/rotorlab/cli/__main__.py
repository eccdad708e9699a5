"""``python -m rotorlab.cli``: the same as the ``rotorlab`` command."""

from rotorlab.cli import main

if __name__ == "__main__":
    main()
