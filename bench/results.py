"""What the small benchmark scripts share: their rows saved as JSON beside the docs (the source of
every figure the README quotes), and printed as a Markdown table."""
import json
import pathlib

DOCS = pathlib.Path(__file__).resolve().parents[1] / "docs"


def save(name, rows, docs=DOCS):
    """Writes <docs>/<name>.json."""
    (docs / f"{name}.json").write_text(json.dumps(rows, indent=1) + "\n")


def publish(name, rows, columns):
    """Writes docs/<name>.json and prints a table; columns: (heading, row -> cell text) pairs."""
    save(name, rows)
    print("| " + " | ".join(h for h, _ in columns) + " |")
    print("|" + "---|" * len(columns))
    for r in rows:
        print("| " + " | ".join(cell(r) for _, cell in columns) + " |")
