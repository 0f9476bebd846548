"""Fruit-map scenarios: the paper's uniform rows and the distributions growers ask about."""
