"""One builder module per node group (NAME, VERSION, TREE_TYPE, build(tree)); helper.py is shared."""
