"""Reading a DCS program's flags from a command list, for the deployment checks
(check_compose.sh, check_kubernetes.sh), as the programs' own parser reads them (CLI11)."""


def flag(command, name):
    """The value of --name=value or --name value in `command`, else None."""
    for i, arg in enumerate(command):
        if arg.startswith(f"--{name}="):
            return arg.split("=", 1)[1]
        if arg == f"--{name}" and i + 1 < len(command):
            return command[i + 1]
    return None
