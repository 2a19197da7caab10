"""Genome files: the document (format 1) and how it is written (JSON, indent 2, a final
newline), so that every builder gives the committed bytes."""
import json
import sys


def genome(inputs, outputs, parameters, description, hidden=(), activation=None):
    """A genome document of an MLP with `hidden` layers (default: a single-layer network)."""
    brain = {"kind": "mlp", "hidden": list(hidden)}
    if activation is not None:
        brain["activation"] = activation
    return {
        "format": 1,
        "brain": brain,
        "inputs": inputs,
        "outputs": outputs,
        "parameters": parameters,
        "origin": {"description": description},
    }


def single_layer(inputs, outputs, rows, description):
    """A single-layer network (mlp, hidden = []) whose first outputs' weight rows are `rows`
    (any further outputs and every bias 0)."""
    extra = [[0.0] * len(inputs) for _ in outputs[len(rows):]]
    parameters = [w for r in rows + extra for w in r] + [0.0] * len(outputs)
    return genome(inputs, outputs, parameters, description)


def dump(document, path=None):
    """Writes `document` to `path`, or to standard output when None or `-`."""
    if path in (None, "-"):
        json.dump(document, sys.stdout, indent=2)
        sys.stdout.write("\n")
        return
    with open(path, "w") as f:
        json.dump(document, f, indent=2)
        f.write("\n")
