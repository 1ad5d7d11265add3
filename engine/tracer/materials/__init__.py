"""Materials as flat tables the kernels read: closures, glasses and emission, built once per render."""
