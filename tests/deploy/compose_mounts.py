"""Reading a service's mounts from `docker-compose config`'s output, for check_compose.sh."""


def mounts(compose, service):
    """(kind, source, target, read_only) of every mount of `service`, kind "volume" or "bind".

    docker-compose 1.29 prints mounts short ("source:target:mode"), v2 long (dicts); a short
    mount is a volume when its source is one of the file's named volumes."""
    named_volumes = compose.get("volumes") or {}
    result = []
    for v in compose["services"][service].get("volumes") or []:
        if isinstance(v, dict):
            result.append((v.get("type"), v.get("source"), v.get("target"),
                           bool(v.get("read_only"))))
            continue
        parts = str(v).split(":")
        source, target = parts[0], parts[1] if len(parts) > 1 else parts[0]
        mode = parts[2] if len(parts) > 2 else "rw"
        kind = "volume" if source in named_volumes else "bind"
        result.append((kind, source, target, "ro" in mode.split(",")))
    return result
